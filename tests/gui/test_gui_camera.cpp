// drumlab-gui's camera and picking driven headless under xvfb-run (--orbit, --zoom, --pick before
// the last frame): an orbit turns the drum's axis across the view, a zoom scales it, and a click
// focuses the front-most particle under the cursor (checked against the particles' projected
// discs), from the front and from behind.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "render/palette.hpp"
#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

struct ViewLine {
  double front_x = 0, front_y = 0, back_x = 0, back_y = 0, rim = 0;
};

ViewLine view_line(const std::string& out) {
  ViewLine v;
  const auto at = out.find("view: ");
  if (at == std::string::npos) return v;
  std::sscanf(out.c_str() + at,
              "view: front axis at (%lf, %lf), back axis at (%lf, %lf), rim %lf px", &v.front_x,
              &v.front_y, &v.back_x, &v.back_y, &v.rim);
  return v;
}

struct PickLine {
  long id = -1;
  double depth = 0, front = 0;
  long under = 0;
};

PickLine pick_line(const std::string& out) {
  PickLine p;
  const auto at = out.find("pick (");
  if (at == std::string::npos) return p;
  const auto colon = out.find("): id ", at);
  if (colon == std::string::npos) return p;
  std::sscanf(out.c_str() + colon,
              "): id %ld entered at depth %lf m; %ld particles under the cursor, the front-most "
              "entered at depth %lf m",
              &p.id, &p.depth, &p.under, &p.front);
  return p;
}

GuiRun run_small(const std::string& name, const std::string& flags) {
  const auto dir = fresh_dir(name);
  const auto scene = write_small_drum(dir, "m5");
  return run_gui(scene.string() + " --settle-time 0.1 --frames 2 --size 900 --height 600 " + flags,
                 true);
}

TEST(GuiCamera, OrbitTurnsTheAxisAcrossTheViewAndZoomScalesIt) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  const GuiRun a = run_small("cam_axis", "--orbit 0,0");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const ViewLine axis = view_line(a.output);
  ASSERT_GT(axis.rim, 100.0) << a.output;
  // Along the axis (parallel projection): the front and back centres coincide at the centre.
  EXPECT_NEAR(axis.front_x, axis.back_x, 0.5);
  EXPECT_NEAR(axis.front_y, axis.back_y, 0.5);
  EXPECT_NEAR(axis.front_x, 450.0, 1.0);

  const GuiRun s = run_small("cam_side", "--orbit 90,0");
  ASSERT_EQ(s.exit_code, 0) << s.output;
  const ViewLine side = view_line(s.output);
  // From the side: the axis lies across the view, as long as the drum is deep.
  EXPECT_GT(std::abs(side.front_x - side.back_x), 20.0) << s.output;
  EXPECT_NEAR(side.front_y, side.back_y, 0.5);

  const GuiRun z = run_small("cam_zoom", "--orbit 0,0 --zoom 2");
  ASSERT_EQ(z.exit_code, 0) << z.output;
  EXPECT_NEAR(view_line(z.output).rim, 2.0 * axis.rim, 0.01 * axis.rim) << z.output;
}

TEST(GuiCamera, PickFocusesTheFrontMostParticleUnderTheCursor) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  // In the bed, below the axis (the axis view's drum fills the 600 px height).
  const auto dir = fresh_dir("pick");
  const auto png = dir / "pick.png";
  const GuiRun f = run_small("pick_front", "--pick 450,500 --screenshot " + png.string());
  ASSERT_EQ(f.exit_code, 0) << f.output;
  const PickLine front = pick_line(f.output);
  ASSERT_GE(front.id, 0) << f.output;
  ASSERT_GE(front.under, 2) << "a pixel in the bed covers particles at several depths";
  EXPECT_NEAR(front.depth, front.front, 1e-7) << f.output;
  // The click focused it: its own cell is drawn.
  EXPECT_GT(pixels_near(read_png(png), render::kOwnCellColor, 30), 20u);

  const GuiRun b = run_small("pick_back", "--orbit 180,0 --pick 450,500");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const PickLine back = pick_line(b.output);
  ASSERT_GE(back.under, 2) << b.output;
  EXPECT_NEAR(back.depth, back.front, 1e-7) << b.output;
  EXPECT_NE(back.id, front.id) << "from behind, another particle is in front";
}

TEST(GuiCamera, BadViewFlagsExitTwo) {
  const GuiRun r = run_gui("--frames 1 --orbit 90", false);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--orbit"), std::string::npos) << r.output;
  const GuiRun p = run_gui("--pick 1,2", false);
  EXPECT_EQ(p.exit_code, 2) << p.output;
}

}  // namespace
}  // namespace drumlab::test
