// drumlab-gui's bad input: one line naming the flag or the file, exit code 2, before any window
// opens (so these run without a display). And the GUI never links OSMesa.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

TEST(GuiInput, UnknownMethodIsOneLine) {
  const auto scene = write_small_drum(fresh_dir("bad-method"), "m5");
  expect_one_line_error(run_gui(scene.string() + " --method m9 --frames 1", false), "--method");
}

TEST(GuiInput, MissingSceneIsOneLine) {
  expect_one_line_error(run_gui("/nonexistent/drum.toml --frames 1", false),
                        "/nonexistent/drum.toml");
}

TEST(GuiInput, BadSwitchAtIsOneLine) {
  const auto scene = write_small_drum(fresh_dir("bad-switch"), "m5");
  expect_one_line_error(run_gui(scene.string() + " --switch-at 10 --frames 1", false),
                        "--switch-at");
  expect_one_line_error(run_gui(scene.string() + " --switch-at x:m2 --frames 1", false),
                        "--switch-at");
  expect_one_line_error(run_gui(scene.string() + " --switch-at 10:m9 --frames 1", false),
                        "--switch-at");
}

TEST(GuiInput, UnknownFocusParticleIsOneLine) {
  const auto scene = write_small_drum(fresh_dir("bad-focus"), "m5");
  expect_one_line_error(run_gui(scene.string() + " --focus 100000 --frames 1", false), "100000");
}

TEST(GuiLink, NeverLinksOsmesa) {
  FILE* pipe = popen(("ldd " + std::string(DRUMLAB_GUI) + " 2>&1; nm -C " +
                      std::string(DRUMLAB_GUI) + " 2>&1 | grep -i osmesa")
                         .c_str(),
                     "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, pipe) != nullptr) out += buf;
  pclose(pipe);
  EXPECT_NE(out.find("libGLX"), std::string::npos) << "ldd ran and lists GLX:\n" << out;
  std::string lower = out;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  EXPECT_EQ(lower.find("osmesa"), std::string::npos) << out;
}

}  // namespace
}  // namespace drumlab::test
