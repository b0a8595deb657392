// The frames a VTU series is written in (engine/io/paraview/view_frame.hpp, `run --frame`): the
// lab frame adds the drum centre's position and velocity, the carrier frame turns with the arm
// so that what turns with it stands still; and the command line's one-line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "engine/io/paraview/view_frame.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

std::string scene_text(bool orbit) {
  return std::string(
             "gravity = [0.0, -9.81, 0.0]\n[drum]\ndiameter = 0.1\ndepth = 0.02\nomega = "
             "2.0\n") +
         (orbit ? "[drum.orbit]\nradius = 0.2\nomega = 5.0\nphase_deg = 90.0\n" : "") +
         "[[particles]]\nradius = 0.004\nvolume_fraction = 1.0\n[material]\ndensity = 2500.0\n"
         "youngs_modulus = 5e6\npoisson_ratio = 0.3\nrestitution = 0.5\nfriction = 0.5\n"
         "[fill]\ncount = 20\nsettle_time = 0.005\n[time]\ndt_factor = 0.2\nduration = 0.01\n";
}

paraview::DataSet one_point(const Vec3& x, const Vec3& v) {
  paraview::DataSet d;
  d.points = {x};
  d.point_data.push_back(
      paraview::make_array("velocity", std::vector<double>{v.x(), v.y(), v.z()}, 3));
  d.point_data.push_back(paraview::make_array("speed", std::vector<double>{v.norm()}));
  d.point_data.push_back(
      paraview::make_array("angular_velocity", std::vector<double>{0.0, 0.0, 5.0}, 3));
  return d;
}

Vec3 vec(const paraview::DataArray& a) {
  const auto& v = std::get<std::vector<double>>(a.values);
  return Vec3(v[0], v[1], v[2]);
}

TEST(ViewFrame, LabAddsTheCentreAndCarrierTurnsWithTheArm) {
  const SceneConfig scene = parse_scene(scene_text(true), "p.toml");
  Particles p;
  p.add(Vec3(0.0, -0.02, 0.01), 0.004, 2500.0);
  const Simulation sim(scene, p);
  // The arm at 90 degrees: the drum's centre at (0, 0.2) from the central axis, moving at
  // Omega R_o = 1 m/s along -x.
  const Vec3 c = sim.carrier_offset();
  EXPECT_NEAR(c.y(), 0.2, 1e-15);
  const Vec3 x(0.01, -0.02, 0.01);
  // A point that turns with the arm: in the drum frame it moves at Omega z x x.
  const Vec3 v = 5.0 * Vec3(-x.y(), x.x(), 0.0);
  paraview::DataSet lab = one_point(x, v);
  paraview::to_frame(lab, paraview::frame_motion(sim, paraview::ViewFrame::lab));
  EXPECT_NEAR((lab.points[0] - (x + c)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((vec(lab.point_data[0]) - (v + Vec3(-1.0, 0.0, 0.0))).norm(), 0.0, 1e-14);
  paraview::DataSet arm = one_point(x, v);
  paraview::to_frame(arm, paraview::frame_motion(sim, paraview::ViewFrame::carrier));
  // The drum's centre sits on +x at R_o; the point is turned by -90 degrees about the axis.
  EXPECT_NEAR((arm.points[0] - Vec3(0.2 + x.y(), -x.x(), x.z())).norm(), 0.0, 1e-15);
  EXPECT_NEAR(vec(arm.point_data[0]).norm(), 0.0, 1e-14);  // at rest with the arm
  EXPECT_NEAR(std::get<std::vector<double>>(arm.point_data[1].values)[0], 0.0, 1e-14);
  EXPECT_NEAR(vec(arm.point_data[2]).z(), 0.0, 1e-15);  // its spin less the arm's
  // The carrier dataset: the central axis and the arm, in the frame asked for.
  const paraview::DataSet lines = paraview::carrier_arm(sim, paraview::ViewFrame::carrier);
  ASSERT_EQ(lines.points.size(), 4u);
  EXPECT_NEAR(lines.points[0].norm(), 0.0, 1e-15);                          // the central axis
  EXPECT_NEAR((lines.points[2] - Vec3(0.2, 0.0, 0.0)).norm(), 0.0, 1e-15);  // the drum's axis
}

TEST(ViewFrame, WithoutAnOrbitEveryFrameIsTheDrumsAndCarrierIsRefused) {
  const SceneConfig scene = parse_scene(scene_text(false), "p.toml");
  Particles p;
  p.add(Vec3(0.0, -0.02, 0.01), 0.004, 2500.0);
  const Simulation sim(scene, p);
  EXPECT_TRUE(paraview::frame_motion(sim, paraview::ViewFrame::lab).identity());
  EXPECT_THROW(paraview::frame_motion(sim, paraview::ViewFrame::carrier), InputError);
  EXPECT_TRUE(paraview::carrier_arm(sim, paraview::ViewFrame::drum).points.empty());
  EXPECT_THROW(paraview::parse_view_frame("arm", "--frame"), InputError);
}

TEST(ViewFrame, RunWritesTheSeriesInTheFrameAndRefusesWhatItCannot) {
  TempDir dir("view-frame");
  const std::string orbit = dir.write("orbit.toml", scene_text(true)).string();
  const std::string plain = dir.write("plain.toml", scene_text(false)).string();
  const std::string out = dir.path().string() + "/vtu";
  auto r = run_cli("run " + orbit + " --steps 20 --every 10 --vtu " + out + " --frame carrier");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f :
       {"particles_000001.vtu", "drum_000001.vtp", "carrier_000001.vtp", "carrier.pvd"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  }
  r = run_cli("run " + plain + " --steps 20 --vtu " + out + "2 --frame carrier");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--frame carrier: the scene has no [drum.orbit]"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(out + "2/particles.pvd"));
  r = run_cli("run " + orbit + " --steps 20 --frame lab");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(
                "--frame: the frame of the VTU series (or of render's pictures): give --vtu DIR"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace drumlab::test
