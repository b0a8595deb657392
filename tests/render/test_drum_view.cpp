// Rendering with DISPLAY unset (OSMesa): a single particle appears in the colour the legend gives
// it, at its projected centre, and the background shows elsewhere.
#include <cstdlib>

#include <gtest/gtest.h>

#include "engine/session/frame_snapshot.hpp"
#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"
#include "tests/render/render_test_helpers.hpp"

namespace drumlab {
namespace {

class DrumViewTest : public ::testing::Test {
 protected:
  void SetUp() override { ::unsetenv("DISPLAY"); }
};

TEST_F(DrumViewTest, OneParticleHasItsLegendColourAtItsProjectedCentre) {
  const double r = 0.02;
  Particles p;
  p.add(Vec3(0.06, -0.04, 0.025), r, 2500.0);
  Simulation sim(test::small_drum_scene(r), std::move(p));
  render::ViewOptions opt;
  opt.width = 320;
  opt.height = 240;
  opt.color_by = render::ColorBy::speed;  // at rest: speed 0, the low end of the legend
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  const render::Image img = view.render(sim);
  if (std::getenv("DRUMLAB_TEST_SAVE") != nullptr) render::write_png(img, "/tmp/one_particle.png");
  ASSERT_EQ(img.width, 320);
  ASSERT_EQ(img.height, 240);

  const auto centre = view.project(sim.particles().position[0]);
  const auto edge = view.project(sim.particles().position[0] + Vec3(r, 0.0, 0.0));
  const double radius_px = edge[0] - centre[0];
  ASSERT_GT(radius_px, 5.0);  // the drum fills the frame: r = 20 mm is ~15 px here
  const int cx = static_cast<int>(centre[0]);
  const int cy = static_cast<int>(centre[1]);
  ASSERT_GT(cx, 0);
  ASSERT_LT(cx, img.width);
  const auto expected = view.legend_color(0.0);
  const double rgb[3] = {expected[0], expected[1], expected[2]};
  // The low end of viridis: dark purple (0.267, 0.005, 0.329).
  EXPECT_EQ(rgb[2] > 0.3 && rgb[1] < 0.05 && rgb[0] < 0.3, true) << "the low end is viridis'";
  // Head-on light: the sphere's centre shows its full diffuse colour (plus a little ambient).
  EXPECT_LE(test::color_distance(img, cx, cy, rgb), 40)
      << "pixel " << int(img.pixel(cx, cy)[0]) << "," << int(img.pixel(cx, cy)[1]) << ","
      << int(img.pixel(cx, cy)[2]);
  // Just outside the sphere (towards the frame's left edge, beyond the drum): not particle colour.
  const int outside = cx + static_cast<int>(1.6 * radius_px);
  EXPECT_GT(test::color_distance(img, outside, cy, rgb), 60);
  // Corners lie outside the drum: background.
  EXPECT_LE(test::color_distance(img, 2, 2, render::kBackground), 2);
  EXPECT_LE(test::color_distance(img, img.width - 3, img.height - 3, render::kBackground), 2);
}

TEST_F(DrumViewTest, ColourFollowsTheChosenQuantity) {
  const double r = 0.02;
  Particles p;
  p.add(Vec3(0.05, 0.02, 0.025), r, 2500.0);  // between the cap's spokes (every 60 degrees)
  p.add(Vec3(-0.07, -0.07, 0.025), r, 2500.0);
  Simulation sim(test::small_drum_scene(r), std::move(p));
  render::ViewOptions opt;
  opt.width = 320;
  opt.height = 240;
  opt.color_by = render::ColorBy::id;  // id 0 blue, id 1 red
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  const render::Image img = view.render(sim);
  for (Index i = 0; i < 2; ++i) {
    const auto c = view.project(sim.particles().position[i]);
    const auto expected = view.legend_color(static_cast<double>(sim.particles().id[i]));
    const double rgb[3] = {expected[0], expected[1], expected[2]};
    EXPECT_LE(test::color_distance(img, static_cast<int>(c[0]), static_cast<int>(c[1]), rgb), 40)
        << "particle " << i;
  }
}

// A scene with [[spray]]: the airborne droplets show as light-blue points where they are, and the
// nozzle's cone is drawn; a snapshot without droplets shows the background there.
TEST_F(DrumViewTest, DropletsAndTheNozzleAreDrawn) {
  SceneConfig scene = test::small_drum_scene(0.01);
  scene.liquid.enabled = true;
  scene.liquid.migration = true;
  scene.liquid.surface_tension = 0.072;
  scene.liquid.max_bridge_volume = 1e-9;
  SprayConfig nozzle;
  nozzle.position = Vec3(0.0, 0.1, 0.025);
  nozzle.direction = Vec3(0.0, -1.0, 0.0);
  nozzle.droplet_radius = 1e-4;
  scene.sprays.push_back(nozzle);
  Particles p;
  p.add(Vec3(-0.08, -0.08, 0.025), 0.01, 2500.0);
  Simulation sim(scene, std::move(p));
  render::ViewOptions opt;
  opt.width = 320;
  opt.height = 240;
  opt.overlay = false;
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  FrameSnapshot snap = render::view_snapshot(sim, opt);
  ASSERT_EQ(snap.sprays.size(), 1u);
  const Vec3 drop(0.08, 0.03, 0.05);  // in front, away from the cone and the particle
  const double blue[3] = {0.55, 0.85, 1.0};
  const render::Image without = view.render(snap);  // places the camera
  const auto at = view.project(drop);
  const int x = static_cast<int>(at[0]), y = static_cast<int>(at[1]);
  EXPECT_GT(test::color_distance(without, x, y, blue), 60);
  snap.droplets.push_back(drop);
  const render::Image with = view.render(snap);
  if (std::getenv("DRUMLAB_TEST_SAVE") != nullptr) render::write_png(with, "/tmp/droplet.png");
  EXPECT_LE(test::color_distance(with, x, y, blue), 60)
      << int(with.pixel(x, y)[0]) << "," << int(with.pixel(x, y)[1]) << ","
      << int(with.pixel(x, y)[2]);
  // The cone's axis: a line below the nozzle, drawn in the nozzle's colour family (blue high).
  const auto on_axis = view.project(Vec3(0.0, 0.06, 0.025));
  bool line = false;
  for (int dx = -2; dx <= 2; ++dx) {
    const auto px = with.pixel(static_cast<int>(on_axis[0]) + dx, static_cast<int>(on_axis[1]));
    line = line || int(px[2]) > int(px[0]) + 60;
  }
  EXPECT_TRUE(line);
}

}  // namespace
}  // namespace drumlab
