// drumlab-gui's --edit goes through the scene validation (engine/scene/scene_validation.hpp): a
// value out of range is one line naming the edit and the scene key, exit 2, and --save-scene
// writes nothing; numbers CLI11 parses (--focus, --orbit, --pick) are range-checked, not wrapped.
// All of these fail before a window opens, so they run without a display.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

TEST(GuiEdit, OutOfRangeEditIsRefusedAndNothingIsSaved) {
  const auto dir = fresh_dir("edit-range");
  const auto scene = write_small_drum(dir, "m5");
  const auto saved = dir / "x.toml";
  const GuiRun r = run_gui(
      scene.string() + " --frames 1 --edit restitution=5 --save-scene " + saved.string(), false);
  expect_one_line_error(r, "--edit 'restitution=5': material.restitution: must be in (0, 1]");
  EXPECT_FALSE(std::filesystem::exists(saved));
}

TEST(GuiEdit, EveryBadValueNamesItsSceneKey) {
  const auto scene = write_small_drum(fresh_dir("edit-keys"), "m5");
  const std::pair<const char*, const char*> cases[] = {
      {"omega=nan", "drum.omega"},
      {"count=1e30", "fill.count"},
      {"count=-1", "fill.count"},
      {"count=0", "fill.count"},
      {"count=100000001", "fill.count"},
      {"seed=-3", "fill.seed"},
      {"fill_fraction=0.9", "fill.volume_fraction"},
      {"settle_time=-1", "fill.settle_time"},
      {"wall_friction=-0.1", "wall.friction"},
      {"rpm=inf", "drum.omega"},
  };
  for (const auto& [edit, key] : cases) {
    SCOPED_TRACE(edit);
    expect_one_line_error(run_gui(scene.string() + " --frames 1 --edit " + edit, false), key);
  }
}

TEST(GuiEdit, FocusBeyondAnIdIsRefusedNotWrapped) {
  const auto scene = write_small_drum(fresh_dir("focus-range"), "m5");
  expect_one_line_error(run_gui(scene.string() + " --frames 1 --focus 4294967296", false),
                        "--focus");
  expect_one_line_error(run_gui(scene.string() + " --frames 1 --focus -1", false), "--focus");
  expect_one_line_error(run_gui(scene.string() + " --frames 1 --orbit 10", false), "--orbit");
  expect_one_line_error(run_gui(scene.string() + " --frames 1 --pick 1,x", false), "--pick");
}

}  // namespace
}  // namespace drumlab::test
