// The focus view for the methods without a single cell grid of their own: a Verlet list (its
// listed partners; the builder's cells of the last rebuild), the multi-level grid (its levels) and
// brute force (no cells, a note). Each frame shows the focus colours; the CLI draws them too.
#include <unistd.h>
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "engine/scene/scene_config.hpp"
#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"
#include "render/grid_overlay.hpp"
#include "render/teach_figure.hpp"
#include "tests/render/render_test_helpers.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab {
namespace {

std::size_t pixels_near(const render::Image& img, const double* rgb, int tolerance) {
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) n += test::color_distance(img, x, y, rgb) <= tolerance;
  }
  return n;
}

/// The particle whose own visit finds the most contacts (so the picture has some to draw).
Index busiest_id(const Simulation& sim) {
  const SearchInput in = sim.search_input();
  Index best = 0;
  std::size_t most = 0;
  for (Index i = 0; i < sim.particles().size(); ++i) {
    const std::size_t c = sim.search().visit(i, in).contacts.size();
    if (c > most) {
      most = c;
      best = i;
    }
  }
  return sim.particles().id[best];
}

class FocusOf : public ::testing::TestWithParam<std::string> {};

TEST_P(FocusOf, FrameShowsTheFocusColours) {
  ::unsetenv("DISPLAY");
  const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml");
  const auto sim = render::teach_simulation(scene, GetParam());
  ASSERT_EQ(sim->search().name(), GetParam());
  render::ViewOptions opt;
  opt.width = 360;
  opt.height = 360;
  opt.focus_id = busiest_id(*sim);
  opt.zoom_to_focus = true;
  opt.overlay = false;
  opt.neutral_particles = true;
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  const render::Image img = view.render(*sim);
  if (std::getenv("DRUMLAB_TEST_SAVE") != nullptr) {
    render::write_png(
        img,
        "/tmp/focus_" + std::string(GetParam() == "verlet:m2" ? "verlet_m2" : GetParam()) + ".png");
  }
  const SearchVisit v = view.focus_visit();
  ASSERT_FALSE(v.contacts.empty());
  EXPECT_GT(pixels_near(img, render::kContactColor, 30), 0u) << "the lines to the contacts";
  const Index i = render::index_of_id(sim->particles(), *opt.focus_id);
  EXPECT_EQ(v.pairs_tested, sim->search().pairs_tested_per_particle()[i]);
  if (v.kind == SearchVisit::Kind::all) {
    EXPECT_TRUE(v.grids.empty());
    EXPECT_EQ(pixels_near(img, render::kOwnCellColor, 30), 0u) << "brute force has no cells";
  } else if (v.kind == SearchVisit::Kind::list) {
    EXPECT_EQ(pixels_near(img, render::kOwnCellColor, 30), 0u) << "a list draws partners, no cells";
  } else if (!v.grids.empty()) {
    EXPECT_GT(pixels_near(img, render::kOwnCellColor, 30), 0u) << "the own cell";
  }
  if (v.kind == SearchVisit::Kind::levels) {
    EXPECT_EQ(v.cells_visited, sim->search().cells_visited_per_particle()[i]);
    EXPECT_TRUE(v.grids.front().has_own);
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, FocusOf, ::testing::Values("verlet:m2", "mlgrid", "brute"),
                         [](const auto& info) {
                           return std::string(info.param == "verlet:m2" ? "verlet_m2" : info.param);
                         });

TEST(FocusCli, RendersTheFocusOfAVerletListWithItsBuildersGridAndOfBruteForce) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("drumlab-focus-cli-" + std::to_string(::getpid()));
  const std::string common = "render " + std::string(DRUMLAB_SCENES_DIR) +
                             "/teach_stencil.toml --steps 20 --settle-time 0 --every 20 --size "
                             "320x240 --focus auto --out ";
  const test::CliResult verlet =
      test::run_cli(common + (dir / "verlet").string() + " --method verlet:m2 --grid");
  ASSERT_EQ(verlet.exit_code, 0) << verlet.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "verlet" / "frame_00001.png"));
  const test::CliResult brute =
      test::run_cli(common + (dir / "brute").string() + " --method brute");
  ASSERT_EQ(brute.exit_code, 0) << brute.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "brute" / "frame_00001.png"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace drumlab
