// drumlab-gui's layout at its default size (1400 x 900): the panels in two side columns, the view
// in the rest. From the "layout" lines a headless --screenshot run prints (the view, the drum's
// disk as drawn, every panel) and from the screenshot itself: no panel covers the disk.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <imgui.h>

#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

struct Rect {
  double x = 0, y = 0, w = 0, h = 0;
  std::string name;
  bool meets(const Rect& o) const {
    return x < o.x + o.w && o.x < x + w && y < o.y + o.h && o.y < y + h;
  }
};

/// The "layout KIND x y w h [name]" lines of the output.
std::vector<Rect> layout(const std::string& output, const std::string& kind) {
  std::vector<Rect> out;
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    std::string head, k;
    Rect r;
    if (!(in >> head >> k) || head != "layout" || k != kind) continue;
    in >> r.x >> r.y >> r.w >> r.h;
    std::getline(in, r.name);
    out.push_back(r);
  }
  return out;
}

/// Pixels of `rgb` (within 3 levels) inside the circle inscribed in `r`, shrunk by 2 pixels.
std::size_t pixels_in_disk(const render::Image& img, const Rect& r, const double* rgb) {
  const double cx = r.x + 0.5 * r.w, cy = r.y + 0.5 * r.h, rad = 0.5 * std::min(r.w, r.h) - 2.0;
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > rad * rad) continue;
      const std::uint8_t* p = &img.rgb[3 * (static_cast<std::size_t>(y) * img.width + x)];
      bool near = true;
      for (int c = 0; c < 3; ++c) near = near && std::abs(p[c] - 255.0 * rgb[c]) <= 3.0;
      n += near ? 1 : 0;
    }
  }
  return n;
}

TEST(GuiLayout, NoPanelCoversTheDrumAtTheDefaultSize) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  const auto dir = fresh_dir("layout");
  const auto scene = write_small_drum(dir, "verlet:m2");
  const auto png = dir / "layout.png";
  const GuiRun r = run_gui(scene.string() + " --settle-time 0.05 --frames 3 --focus auto --teach " +
                               "--screenshot " + png.string(),
                           true);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const render::Image img = read_png(png);
  ASSERT_EQ(img.width, 1400) << r.output;
  ASSERT_EQ(img.height, 900);
  const std::vector<Rect> view = layout(r.output, "view");
  const std::vector<Rect> drum = layout(r.output, "drum");
  const std::vector<Rect> panels = layout(r.output, "panel");
  ASSERT_EQ(view.size(), 1u) << r.output;
  ASSERT_EQ(drum.size(), 1u) << r.output;
  ASSERT_GE(panels.size(), 6u) << "Run, Scene, View, Search, Export, Teaching, Focus inset\n"
                               << r.output;
  const Rect& d = drum.front();
  EXPECT_GT(d.w, 400.0) << "the disk fills the view";
  EXPECT_GE(d.x, view.front().x);
  EXPECT_LE(d.x + d.w, view.front().x + view.front().w);
  EXPECT_GE(d.y, 0.0);
  EXPECT_LE(d.y + d.h, 900.0);
  for (const Rect& p : panels) {
    EXPECT_FALSE(p.meets(d)) << "panel" << p.name << " covers the drum";
    EXPECT_FALSE(p.meets(view.front())) << "panel" << p.name << " covers the view";
  }
  // The screenshot agrees: the active panel's title bar (opaque blue; the old layout put the Focus
  // inset's on the disk) is nowhere inside the disk, and it is drawn somewhere.
  ImGuiContext* ctx = ImGui::CreateContext();
  ImGui::StyleColorsDark();
  const ImVec4 c = ImGui::GetStyle().Colors[ImGuiCol_TitleBgActive];
  ImGui::DestroyContext(ctx);
  const double title[3] = {c.x, c.y, c.z};
  EXPECT_EQ(pixels_in_disk(img, d, title), 0u);
  EXPECT_GT(pixels_near(img, title, 3), 100u) << "a panel's title bar";
}

}  // namespace
}  // namespace drumlab::test
