// A scene edited in drumlab-gui's scene panel and saved as TOML loads back to the edited scene.
#include <gtest/gtest.h>

#include <numbers>

#include "engine/scene/scene_config.hpp"
#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

TEST(GuiScene, EditedSceneSavedAndLoadedBackIsTheEditedOne) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  const auto dir = fresh_dir("scene-save");
  const auto scene = write_small_drum(dir, "m2");
  const auto saved = dir / "edited.toml";
  const GuiRun r = run_gui(scene.string() +
                               " --settle-time 0 --frames 1 --edit rpm=12.5 --edit friction=0.3 "
                               "--edit restitution=0.7 --edit wall_friction=0.2 --edit count=250 "
                               "--edit seed=7 --save-scene " +
                               saved.string(),
                           true);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  SceneConfig expected = load_scene(scene);
  expected.drum.omega = 12.5 * 2.0 * std::numbers::pi / 60.0;
  expected.material.friction = 0.3;
  expected.material.restitution = 0.7;
  expected.wall.friction = 0.2;
  expected.fill.count = 250;
  expected.fill.seed = 7;
  SceneConfig loaded = load_scene(saved);
  EXPECT_NE(loaded, load_scene(scene)) << "the edits are in the file";
  loaded.source = expected.source;  // where each came from
  EXPECT_EQ(loaded, expected);
  EXPECT_EQ(loaded.output.diagnostics_every, load_scene(scene).output.diagnostics_every)
      << "the GUI's own stability-check interval is not saved";
}

}  // namespace
}  // namespace drumlab::test
