// A method switched at step K inside drumlab-gui gives bit-identical particles to a headless
// RunSession with the same switch at K (the GUI steps in its own thread, in chunks, and takes
// snapshots between them: none of that may change the trajectory).
#include <gtest/gtest.h>

#include "engine/io/checkpoint.hpp"
#include "engine/session/run_session.hpp"
#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

TEST(GuiSwitch, SwitchAtStepIsBitIdenticalToAHeadlessRun) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  const auto dir = fresh_dir("switch");
  const auto scene = write_small_drum(dir, "m5");
  const auto ck = dir / "final.h5";
  // 6 frames of 10 steps; the switch at 25 falls inside the third chunk.
  const GuiRun r = run_gui(scene.string() +
                               " --settle-time 0.02 --method m5 --switch-at "
                               "25:verlet:m2 --frames 6 --steps-per-frame 10 --focus 3 "
                               "--checkpoint " +
                               ck.string(),
                           true);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Checkpoint gui = read_checkpoint(ck);

  SessionOptions o;
  o.scene_file = scene.string();
  o.method = "m5";
  o.settle_time = 0.02;
  RunSession session(load_dynamic_scene(scene.string()), o);
  session.settle();
  session.advance(25);
  session.set_search_method("verlet:m2");
  session.advance(35);
  const Simulation& sim = session.simulation();

  EXPECT_EQ(gui.state.steps, sim.steps());
  EXPECT_EQ(gui.state.search_method, "verlet:m2");
  ASSERT_EQ(gui.state.particles.size(), sim.particles().size());
  EXPECT_EQ(differing_motion(gui.state.particles, sim.particles()), 0u)
      << "position/velocity/omega components that differ in any bit";
}

}  // namespace
}  // namespace drumlab::test
