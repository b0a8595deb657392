// The triangle walls in the drum picture (render/wall_mesh_actors.hpp): a lifter is drawn in the
// walls' colour where its points project, and turns with the drum's angle; a mesh fixed in the
// lab stands still; the walls toggle hides them; a planetary drum's picture moves them with the
// frame like the mantle. A snapshot carries the meshes themselves (shared, not the Simulation).
#include <cmath>
#include <cstdlib>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "engine/mesh/stl_file.hpp"
#include "engine/session/frame_snapshot.hpp"
#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"
#include "tests/render/render_test_helpers.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/mesh_test_shapes.hpp"

namespace drumlab {
namespace {

constexpr double kLifterPhase = 30.0 * std::numbers::pi / 180.0;  // between two spokes

MeshMaterial wall_material(const SceneConfig& s) {
  return {s.wall.youngs_modulus, s.wall.poisson_ratio, s.wall.restitution, s.wall.friction,
          s.wall.rolling_friction};
}

/// The render tests' drum (D = 0.3 m, H = 0.05 m) with one straight lifter 0.04 m high and
/// 0.012 m thick at 30 degrees and, given a file, a lab-fixed plate from it.
SceneConfig lifter_scene(const std::filesystem::path& plate = {}) {
  SceneConfig s = test::small_drum_scene(0.01);
  LifterWallConfig lifter;
  lifter.count = 1;
  lifter.height = 0.04;
  lifter.thickness = 0.012;  // wide enough to hit in the small lab-frame picture of an orbit
  lifter.phase_deg = 30.0;
  lifter.material = wall_material(s);
  s.lifters.push_back(lifter);
  if (!plate.empty()) {
    MeshWallConfig m;
    m.file = plate;
    m.attach = MeshAttach::lab;
    m.material = wall_material(s);
    s.meshes.push_back(m);
  }
  return s;
}

/// A square plate (0.03 m a side) facing the camera (+z) at (-0.07, -0.05, H/2), as an STL file.
std::filesystem::path write_plate(const test::TempDir& dir) {
  const auto corners =
      test::grid_square(2, Vec3(-0.07, -0.05, 0.025), Vec3::UnitX(), Vec3::UnitY(), 0.015);
  const auto file = dir.path() / "plate.stl";
  write_stl(make_mesh(corners, 0.3, "plate"), file);
  return file;
}

Particles one_particle() {
  Particles p;
  p.add(Vec3(0.0, 0.0, 0.025), 0.01, 2500.0);
  return p;
}

/// The middle of the lifter's blade (half its height in from the mantle) in the drum frame, the
/// drum turned by `angle`.
Vec3 lifter_middle(double angle) {
  const double r = 0.15 - 0.02;
  return Vec3(r * std::cos(kLifterPhase + angle), r * std::sin(kLifterPhase + angle), 0.025);
}

int wall_distance(const render::Image& img, const std::array<double, 2>& at) {
  return test::color_distance(img, static_cast<int>(std::lround(at[0])),
                              static_cast<int>(std::lround(at[1])), render::kMeshWallColor);
}

class WallMeshViewTest : public ::testing::Test {
 protected:
  void SetUp() override { ::unsetenv("DISPLAY"); }
};

/// Lit face-on by the headlight, the walls' flat faces come out within this many levels of their
/// colour (the specular highlight brightens them a little); the back cap, the background and the
/// particles' colours are all far further away.
constexpr int kWallTolerance = 40;

TEST(WallMeshSnapshot, CarriesTheSimulationsMeshesAndNoneWithout) {
  const Simulation sim(lifter_scene(), one_particle());
  const FrameSnapshot s = take_snapshot(sim, {});
  ASSERT_NE(s.meshes, nullptr);
  EXPECT_EQ(s.meshes, sim.wall_meshes());  // shared, not copied
  ASSERT_EQ(s.meshes->size(), 1u);
  EXPECT_EQ((*s.meshes)[0].key, "wall.lifters[0]");
  const Simulation plain(test::small_drum_scene(0.01), one_particle());
  EXPECT_EQ(take_snapshot(plain, {}).meshes, nullptr);
}

TEST_F(WallMeshViewTest, ALifterTurnsWithTheDrumAndALabMeshStandsStill) {
  test::TempDir dir("wall-mesh-view");
  const Simulation sim(lifter_scene(write_plate(dir)), one_particle());
  render::ViewOptions opt;
  opt.width = 640;
  opt.height = 480;
  opt.overlay = false;
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  FrameSnapshot s = render::view_snapshot(sim, opt);
  const Vec3 plate(-0.07, -0.05, 0.025);
  std::array<double, 2> before{};
  for (const double angle : {0.0, 1.0}) {
    s.drum_angle = angle;
    const render::Image img = view.render(s);
    if (std::getenv("DRUMLAB_TEST_SAVE") != nullptr) {
      render::write_png(img, "/tmp/wall_mesh_" + std::to_string(angle) + ".png");
    }
    const auto at = view.project(lifter_middle(angle));
    EXPECT_LE(wall_distance(img, at), kWallTolerance) << "the lifter at drum angle " << angle;
    EXPECT_LE(wall_distance(img, view.project(plate)), kWallTolerance)
        << "the lab plate at drum angle " << angle;
    if (angle == 0.0) {
      before = at;
    } else {  // the lifter has left the place it had: the back cap shows there now
      EXPECT_GT(std::hypot(at[0] - before[0], at[1] - before[1]), 50.0);
      EXPECT_GT(wall_distance(img, before), 100);
      EXPECT_LE(
          test::color_distance(img, static_cast<int>(std::lround(before[0])),
                               static_cast<int>(std::lround(before[1])), render::kBackCapColor),
          10);
    }
  }
  // The walls toggle hides the meshes with the mantle and the caps.
  opt.walls = false;
  view.set_options(opt);
  const render::Image hidden = view.render(s);
  EXPECT_GT(wall_distance(hidden, view.project(lifter_middle(1.0))), 100);
  EXPECT_GT(wall_distance(hidden, view.project(plate)), 100);
}

TEST_F(WallMeshViewTest, APlanetaryDrumsLifterFollowsThePicturesFrame) {
  SceneConfig scene = lifter_scene();
  scene.drum.orbit.radius = 0.4;
  scene.drum.orbit.omega = 3.0;
  scene.drum.orbit.phase = 2.0;
  const Simulation sim(scene, one_particle());
  for (const auto frame : {paraview::ViewFrame::carrier, paraview::ViewFrame::lab}) {
    render::ViewOptions opt;
    opt.width = 640;
    opt.height = 480;
    opt.overlay = false;
    opt.frame = frame;
    render::OffscreenContext context(opt.width, opt.height);
    render::DrumView view(opt, context);
    FrameSnapshot s = render::view_snapshot(sim, opt);
    s.drum_angle = 0.5;
    const render::Image img = view.render(s);
    const auto at = view.project(lifter_middle(0.5));  // the frame's motion is project()'s
    const auto centre = view.project(Vec3(0.0, 0.0, 0.025));
    EXPECT_GT(std::hypot(at[0] - centre[0], at[1] - centre[1]), 20.0);
    EXPECT_LE(wall_distance(img, at), kWallTolerance) << paraview::view_frame_name(frame);
  }
}

}  // namespace
}  // namespace drumlab
