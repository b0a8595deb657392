// A frame of the demo drum (18,825 particles right after the fill) is not blank: the bed covers a
// good part of the drum, in the three size colours of the legend.
#include <cstdlib>

#include <gtest/gtest.h>

#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"
#include "tests/render/render_test_helpers.hpp"

namespace drumlab {
namespace {

TEST(DemoFrame, IsNotBlankAndShowsTheThreeSizes) {
  ::unsetenv("DISPLAY");
  const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/drum_demo.toml");
  Simulation sim(scene, random_fill(scene));
  render::ViewOptions opt;
  opt.width = 640;
  opt.height = 360;
  opt.color_by = render::ColorBy::size;
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  const render::Image img = view.render(sim);
  if (std::getenv("DRUMLAB_TEST_SAVE") != nullptr) render::write_png(img, "/tmp/demo_frame.png");

  EXPECT_GT(test::non_background_share(img, render::kBackground), 0.25);
  // Pixels close to each size's legend colour (the sphere centres face the light).
  for (double r_mm : {5.0, 10.0, 15.0}) {
    const auto c = view.legend_color(r_mm);
    const double rgb[3] = {c[0], c[1], c[2]};
    std::size_t close = 0;
    for (int y = 0; y < img.height; ++y) {
      for (int x = 0; x < img.width; ++x) {
        if (test::color_distance(img, x, y, rgb) <= 25) ++close;
      }
    }
    EXPECT_GT(close, 500u) << "radius " << r_mm << " mm";
  }
  // The upper half of the drum is empty after the fill: mostly the dark back cap there.
  const auto top = view.project(Vec3(0.0, 0.35, 0.0));
  EXPECT_LE(test::color_distance(img, static_cast<int>(top[0]) + 7, static_cast<int>(top[1]),
                                 render::kBackCapColor),
            12);
}

}  // namespace
}  // namespace drumlab
