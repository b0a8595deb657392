// A planetary drum's pictures (ViewOptions::frame): in the carrier arm's frame the central axis
// stands straight above the drum's centre at R_o and the carrier's field points down, whatever
// the arm's angle; a particle is drawn where the frame's motion puts it (project() takes
// drum-frame points), and picking (sight_line) gives drum-frame points back; the lab frame puts
// the central axis at the picture's centre; a drum without an orbit is drawn as before.
#include <cmath>
#include <cstdlib>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "engine/session/frame_snapshot.hpp"
#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"
#include "tests/render/render_test_helpers.hpp"

namespace drumlab {
namespace {

constexpr double kArmColor[3] = {1.0, 0.6, 0.2};

SceneConfig planetary_scene(double phase) {
  SceneConfig s = test::small_drum_scene(0.02);
  s.drum.orbit.radius = 0.25;
  s.drum.orbit.omega = 3.0;
  s.drum.orbit.phase = phase;
  return s;
}

class CarrierViewTest : public ::testing::Test {
 protected:
  void SetUp() override { ::unsetenv("DISPLAY"); }
};

TEST(PictureMotion, TheArmsFrameTurnsTheFieldDownAndTheLabFrameCentresTheAxis) {
  for (const double phase : {0.0, 1.0, 2.5, -2.0}) {
    Particles p;
    p.add(Vec3(0.05, 0.0, 0.025), 0.02, 2500.0);
    const Simulation sim(planetary_scene(phase), std::move(p));
    const FrameSnapshot s = take_snapshot(sim, {});
    const auto carrier = render::picture_motion(s, paraview::ViewFrame::carrier);
    // The field's direction c turned by the motion points straight down.
    const Vec3 c = Eigen::AngleAxisd(carrier.turn, Vec3::UnitZ()) * s.carrier_offset;
    EXPECT_NEAR(c.x(), 0.0, 1e-15);
    EXPECT_NEAR(c.y(), -0.25, 1e-15);
    const auto lab = render::picture_motion(s, paraview::ViewFrame::lab);
    EXPECT_EQ(lab.offset, s.carrier_offset);  // the central axis (-c) at the origin
    EXPECT_TRUE(render::picture_motion(s, paraview::ViewFrame::drum).identity());
  }
}

TEST_F(CarrierViewTest, TheCentralAxisStandsAboveTheDrumAndPickingGivesDrumFramePoints) {
  for (const double phase : {0.0, 2.0}) {
    const double r = 0.02;
    Particles p;
    p.add(Vec3(0.08, 0.03, 0.025), r, 2500.0);
    const Simulation sim(planetary_scene(phase), std::move(p));
    render::ViewOptions opt;
    opt.width = 320;
    opt.height = 240;
    render::OffscreenContext context(opt.width, opt.height);
    render::DrumView view(opt, context);
    const render::Image img = view.render(sim);
    if (std::getenv("DRUMLAB_TEST_SAVE") != nullptr) render::write_png(img, "/tmp/carrier.png");
    // The central axis, at -c in the drum frame: above the drum's centre, in the arm's colour.
    const auto centre = view.project(Vec3(0.0, 0.0, 0.05));
    const auto axis =
        view.project(Vec3(-sim.carrier_offset().x(), -sim.carrier_offset().y(), 0.05));
    EXPECT_NEAR(axis[0], centre[0], 1.0);
    EXPECT_LT(axis[1], centre[1] - 50.0);  // rows count from the top
    EXPECT_LE(
        test::color_distance(img, static_cast<int>(axis[0]), static_cast<int>(axis[1]), kArmColor),
        10)
        << "phase " << phase;
    // The particle is where the motion puts it, and the line of sight through it meets it.
    const Vec3 x = sim.particles().position[0];
    const auto at = view.project(x);
    const auto sight = view.sight_line(at[0], at[1]);
    const Vec3 d = (sight[1] - sight[0]).normalized();
    const Vec3 off = (x - sight[0]) - d.dot(x - sight[0]) * d;  // x's distance from the line
    EXPECT_LT(off.norm(), 0.01 * r) << "phase " << phase;
    const std::vector<Vec3> centres{x};
    const std::vector<double> radii{r};
    EXPECT_TRUE(render::first_sphere_hit(sight[0], sight[1], centres, radii).has_value());
  }
}

TEST_F(CarrierViewTest, TheLabFrameCentresTheCentralAxisAndAPlainDrumIsUnmoved) {
  Particles p;
  p.add(Vec3(0.08, 0.03, 0.025), 0.02, 2500.0);
  const Simulation sim(planetary_scene(1.0), std::move(p));
  render::ViewOptions opt;
  opt.width = 320;
  opt.height = 240;
  opt.frame = paraview::ViewFrame::lab;
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  (void)view.render(sim);
  const Vec3 c = sim.carrier_offset();
  const auto axis = view.project(Vec3(-c.x(), -c.y(), 0.025));
  EXPECT_NEAR(axis[0], 160.0, 1.0);
  EXPECT_NEAR(axis[1], 120.0, 1.0);

  Particles q;
  q.add(Vec3(0.08, 0.03, 0.025), 0.02, 2500.0);
  const Simulation plain(test::small_drum_scene(0.02), std::move(q));
  render::OffscreenContext context2(opt.width, opt.height);
  render::DrumView plain_view(opt, context2);  // the lab frame asked: a plain drum is its own
  (void)plain_view.render(plain);
  const auto centre = plain_view.project(Vec3(0.0, 0.0, 0.025));
  EXPECT_NEAR(centre[0], 160.0, 1.0);
  EXPECT_NEAR(centre[1], 120.0, 1.0);
  const auto right = plain_view.project(Vec3(0.1, 0.0, 0.025));
  EXPECT_GT(right[0], centre[0] + 10.0);
  EXPECT_NEAR(right[1], centre[1], 1.0);
}

}  // namespace
}  // namespace drumlab
