// drumlab-gui on a scene with triangle walls ([[wall.lifters]]): the view draws the lifters in the
// walls' colour (the GUI renders through render::DrumView), and the scene panel saves the scene
// with its walls so that it loads back the same.
#include <gtest/gtest.h>

#include <fstream>

#include "engine/scene/scene_config.hpp"
#include "render/palette.hpp"
#include "tests/gui/gui_test_helpers.hpp"
#include "tests/small_drum_text.hpp"

namespace drumlab::test {
namespace {

/// The GUI's screenshot of `scene_text` and the scene it saves.
struct Shot {
  GuiRun run;
  render::Image image;
};

Shot shoot(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const auto scene = dir / (name + ".toml");
  std::ofstream(scene) << text;
  const auto png = dir / (name + ".png");
  Shot s;
  s.run = run_gui(scene.string() + " --settle-time 0 --frames 1 --size 900 --height 600 " +
                      "--save-scene " + (dir / (name + "_saved.toml")).string() + " --screenshot " +
                      png.string(),
                  true);
  s.image = read_png(png);
  return s;
}

TEST(GuiMeshes, LiftersAreDrawnAndTheSceneIsSavedWithThem) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  const auto dir = fresh_dir("meshes");
  SmallDrumText plain;
  plain.header = "name = \"gui_lifters\"\n";
  SmallDrumText lifters = plain;
  lifters.wall = "friction = 0.5\n[[wall.lifters]]\ncount = 6\nheight = 0.03\nthickness = 0.008";
  const Shot with = shoot(dir, "lifters", lifters.text());
  const Shot without = shoot(dir, "plain", plain.text());
  ASSERT_EQ(with.run.exit_code, 0) << with.run.output;
  ASSERT_EQ(without.run.exit_code, 0) << without.run.output;
  ASSERT_EQ(with.image.width, 900);
  // Six blades 30 mm x 8 mm in a 200 mm drum about 500 pixels high: hundreds of pixels each.
  const std::size_t lit = pixels_near(with.image, render::kMeshWallColor, 40);
  const std::size_t base = pixels_near(without.image, render::kMeshWallColor, 40);
  EXPECT_GT(lit, base + 1000) << "walls' colour: " << lit << " with lifters, " << base
                              << " without";
  SceneConfig saved = load_scene(dir / "lifters_saved.toml");
  SceneConfig original = load_scene(dir / "lifters.toml");
  ASSERT_EQ(saved.lifters.size(), 1u);
  EXPECT_EQ(saved.lifters, original.lifters);
  EXPECT_EQ(saved.wall, original.wall);
}

}  // namespace
}  // namespace drumlab::test
