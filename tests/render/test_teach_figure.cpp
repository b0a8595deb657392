// `teach`: five panels, one per method, whose counters (counted from the cells and candidates the
// panel draws) equal the engine's own per-particle counters of the step that produced the state.
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "app/bench/stress_scene.hpp"
#include "engine/scene/scene_config.hpp"
#include "render/drum_view.hpp"
#include "render/grid_overlay.hpp"
#include "render/teach_figure.hpp"
#include "tests/render/render_test_helpers.hpp"

namespace drumlab {
namespace {

SceneConfig teach_scene() {
  return load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml");
}

/// Share of the columns [x0, x0 + w) showing the own-cell colour somewhere.
bool panel_shows_own_cell(const render::Image& img, int x0, int w) {
  for (int y = 0; y < img.height; ++y) {
    for (int x = x0; x < x0 + w; ++x) {
      if (test::color_distance(img, x, y, render::kOwnCellColor) <= 30) return true;
    }
  }
  return false;
}

TEST(TeachFigure, PanelCountersEqualTheEnginesPerParticleCounters) {
  ::unsetenv("DISPLAY");
  const SceneConfig scene = teach_scene();
  constexpr int kW = 220, kH = 260;
  const render::TeachFigure fig = render::make_teach_figure(scene, std::nullopt, kW, kH);
  ASSERT_EQ(fig.panels.size(), 5u);
  EXPECT_EQ(fig.image.width, 5 * kW);
  EXPECT_EQ(fig.image.height, kH);
  std::set<std::size_t> distinct_cells;
  for (std::size_t k = 0; k < fig.panels.size(); ++k) {
    const render::TeachPanel& panel = fig.panels[k];
    SCOPED_TRACE(panel.method);
    const char* const expected[] = {"m1", "m2", "m3", "m4", "m5"};
    EXPECT_EQ(panel.method, expected[k]);
    const auto sim = render::teach_simulation(scene, panel.method);
    ASSERT_EQ(sim->search().name(), panel.method);
    const Index i = render::index_of_id(sim->particles(), fig.particle_id);
    EXPECT_EQ(panel.cells_visited, sim->search().cells_visited_per_particle()[i]);
    EXPECT_EQ(panel.pairs_tested, sim->search().pairs_tested_per_particle()[i]);
    EXPECT_GT(panel.pairs_tested, 0u);
    EXPECT_LE(panel.contacts, panel.pairs_tested);
    EXPECT_TRUE(panel_shows_own_cell(fig.image, static_cast<int>(k) * kW, kW));
    distinct_cells.insert(panel.cells_visited);
  }
  EXPECT_GE(distinct_cells.size(), 4u) << "the methods visit different numbers of cells";
}

TEST(TeachFigure, EveryParticleOfEveryMethodMatchesItsTrace) {
  // The replayed search (what the panels draw) against the hot loop, for all 502 particles.
  const SceneConfig scene = teach_scene();
  for (const std::string& m : render::teach_methods()) {
    SCOPED_TRACE(m);
    const auto sim = render::teach_simulation(scene, m);
    const auto* grid = dynamic_cast<const CellGridSearch*>(&sim->search());
    ASSERT_NE(grid, nullptr);
    std::uint64_t found = 0;
    for (Index i = 0; i < sim->particles().size(); ++i) {
      const SearchTrace t = grid->trace(i);
      ASSERT_EQ(t.cells_visited(), sim->search().cells_visited_per_particle()[i]) << i;
      ASSERT_EQ(t.candidates.size(), sim->search().pairs_tested_per_particle()[i]) << i;
      found += t.contacts.size();
    }
    EXPECT_EQ(found, sim->search().counters().pairs_found);
  }
}

TEST(TeachFigure, UnknownParticleIsAnInputError) {
  ::unsetenv("DISPLAY");
  EXPECT_THROW(render::make_teach_figure(teach_scene(), Index{999999}, 64, 64), InputError);
}

TEST(TeachFigure, TeachesAFileFillScene) {
  ::unsetenv("DISPLAY");
  const auto dir = std::filesystem::temp_directory_path() /
                   ("drumlab-teach-file-fill-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  bench::StressScene s;
  s.fill_file = "packing.csv";
  s.settle_time = 0.002;
  bench::write_text(dir / s.fill_file, bench::lattice_csv(s, 0.004, 0.02, 60));
  const SceneConfig scene = load_scene(bench::write_text(dir / "file_fill.toml", s.toml()));
  const auto sim = render::teach_simulation(scene, "m1");
  EXPECT_EQ(sim->particles().size(), 60u);
  const render::TeachFigure fig = render::make_teach_figure(scene, std::nullopt, 64, 64);
  EXPECT_EQ(fig.panels.size(), 5u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace drumlab
