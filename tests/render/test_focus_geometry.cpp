// The focus picture lines up with the particles: the focus particle's marker is drawn inside its
// own cell, whose outline is drawn around it.
#include <cstdlib>

#include <gtest/gtest.h>

#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"
#include "render/grid_overlay.hpp"
#include "tests/render/render_test_helpers.hpp"

namespace drumlab {
namespace {

TEST(FocusGeometry, MarkerSitsInsideTheOwnCellOutline) {
  ::unsetenv("DISPLAY");
  const double r = 0.01;
  Particles p;
  p.add(Vec3(-0.05, -0.05, 0.02), r, 2500.0);
  p.add(Vec3(0.004, -0.013, 0.03), r, 2500.0);  // the focus
  p.add(Vec3(0.05, 0.04, 0.02), r, 2500.0);
  Simulation sim(test::small_drum_scene(r), std::move(p));
  render::ViewOptions opt;
  opt.width = 400;
  opt.height = 400;
  opt.focus_id = 1;
  opt.zoom_to_focus = true;
  opt.overlay = false;
  opt.neutral_particles = true;
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  const render::Image img = view.render(sim);
  if (std::getenv("DRUMLAB_TEST_SAVE") != nullptr) render::write_png(img, "/tmp/focus.png");
  const Vec3 x = sim.particles().position[1];
  const auto c = view.project(x);
  const int cx = static_cast<int>(c[0]), cy = static_cast<int>(c[1]);
  const double white[3] = {1.0, 1.0, 1.0};
  EXPECT_LE(test::color_distance(img, cx, cy, white), 30) << "the focus marker";
  // The own cell's outline encloses the marker: walking left and right from the centre meets it
  // within one cell width each way.
  const auto* grid = dynamic_cast<const CellGridSearch*>(&sim.search());
  ASSERT_NE(grid, nullptr);
  const double cell_px = view.project(x + Vec3(grid->geometry().cell_xy, 0.0, 0.0))[0] - c[0];
  ASSERT_GT(cell_px, 20.0);
  auto meets_outline = [&](int step) {
    for (int k = 1; k <= static_cast<int>(cell_px) + 2; ++k) {
      if (test::color_distance(img, cx + step * k, cy, render::kOwnCellColor) <= 40) return true;
    }
    return false;
  };
  EXPECT_TRUE(meets_outline(-1));
  EXPECT_TRUE(meets_outline(+1));
}

}  // namespace
}  // namespace drumlab
