// drumlab-gui under xvfb-run: the saved window shows ImGui's widgets, the particles and the focus
// particle's search, and the teaching mode walks it with each cell-grid method. Skipped only
// where xvfb-run is missing.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <imgui.h>

#include "engine/search/search_methods.hpp"
#include "engine/session/frame_snapshot.hpp"
#include "engine/session/run_session.hpp"
#include "render/grid_overlay.hpp"
#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

/// ImGui's dark style colour `col` (the style drumlab-gui uses), RGB in [0, 1].
std::array<double, 3> imgui_dark(ImGuiCol col) {
  ImGuiContext* ctx = ImGui::CreateContext();
  ImGui::StyleColorsDark();
  const ImVec4 c = ImGui::GetStyle().Colors[col];
  ImGui::DestroyContext(ctx);
  return {c.x, c.y, c.z};
}

TEST(GuiWindow, ScreenshotShowsWidgetsParticlesAndTheFocus) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  const auto dir = fresh_dir("window");
  const auto scene = write_small_drum(dir, "m5");
  const auto png = dir / "window.png";
  const GuiRun r = run_gui(scene.string() +
                               " --settle-time 0.3 --frames 5 --focus auto "
                               "--zoom-to-focus --size 900 --height 600 --screenshot " +
                               png.string(),
                           true);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const render::Image img = read_png(png);
  ASSERT_EQ(img.width, 900) << r.output;
  ASSERT_EQ(img.height, 600);
  // Widgets: the check marks (walls, legend) and the slider grab (steps / frame), opaque.
  const auto check = imgui_dark(ImGuiCol_CheckMark);
  const auto grab = imgui_dark(ImGuiCol_SliderGrab);
  EXPECT_GT(pixels_near(img, check.data(), 3), 20u) << "ImGui check marks";
  EXPECT_GT(pixels_near(img, grab.data(), 3), 20u) << "ImGui slider grab";
  // Particles: the two size classes' Okabe-Ito colours (shaded spheres: a wider tolerance).
  EXPECT_GT(pixels_near(img, render::kCategories[0], 40), 500u) << "small particles";
  EXPECT_GT(pixels_near(img, render::kCategories[1], 40), 500u) << "large particles";
  // The focus particle's search: its own cell's outline and its contacts.
  EXPECT_GT(pixels_near(img, render::kOwnCellColor, 30), 20u) << "own cell";
  EXPECT_GT(pixels_near(img, render::kForwardCellColor, 60), 20u) << "visited half stencil";
  EXPECT_GT(pixels_near(img, render::kContactColor, 30), 0u) << "contacts";
}

TEST(GuiWindow, TeachingModeShowsEveryCellGridMethod) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  const auto dir = fresh_dir("teach");
  const auto scene = write_small_drum(dir, "m5");
  // Each method's whole search of the focus particle on the state the GUI ends on (30 steps
  // after 0.1 s of settling; the GUI's run has the same bits): what its teaching line must say.
  const std::vector<std::string> methods = cell_grid_method_names();
  ASSERT_EQ(methods.size(), 5u);
  SessionOptions o;
  o.scene_file = scene.string();
  o.settle_time = 0.1;
  RunSession session(load_dynamic_scene(scene.string()), o);
  session.settle();
  session.advance(30);
  SnapshotRequest request;
  request.focus_id = 0;
  request.compare_methods = methods;
  const FrameSnapshot expected = take_snapshot(session.simulation(), request);
  ASSERT_EQ(expected.compare_visits.size(), methods.size());
  std::set<std::string> distinct;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const MethodVisit& mv = expected.compare_visits[m];
    ASSERT_EQ(mv.method, methods[m]);
    // One cell walked of the whole search: the own cell, whatever it holds.
    const std::string line =
        fmt::format("teach {}: cells 1 / {}, ", mv.method, mv.visit.cells_visited);
    const std::string whole = fmt::format(" / {}, contacts ", mv.visit.pairs_tested);
    distinct.insert(fmt::format("{} {}", mv.visit.cells_visited, mv.visit.pairs_tested));
    const auto png = dir / ("teach_" + mv.method + ".png");
    const GuiRun r = run_gui(
        scene.string() + " --settle-time 0.1 --frames 3 --focus 0 --teach " + "--teach-method " +
            mv.method + " --teach-cells 1 --size 900 --height 600 --screenshot " + png.string(),
        true);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto at = r.output.find(line);
    ASSERT_NE(at, std::string::npos) << "expected \"" << line << "\" in:\n" << r.output;
    EXPECT_NE(r.output.find(whole, at), std::string::npos)
        << mv.method << " tests " << mv.visit.pairs_tested << " candidates:\n"
        << r.output;
    const render::Image img = read_png(png);
    ASSERT_EQ(img.width, 900) << r.output;
    // One cell walked: the own cell is drawn, no visited stencil cell yet.
    EXPECT_GT(pixels_near(img, render::kOwnCellColor, 30), 20u) << mv.method << ": own cell";
    EXPECT_EQ(pixels_near(img, render::kForwardCellColor, 3), 0u)
        << mv.method << ": no forward cell yet";
  }
  EXPECT_GE(distinct.size(), 3u) << "the methods' searches differ: the lines tell them apart";
}

}  // namespace
}  // namespace drumlab::test
