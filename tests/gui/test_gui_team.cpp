// drumlab-gui --threads 2 with the adaptive team (the default) runs its windows of steps on 2 and
// on 1 thread and still gives the bits of a one-thread headless RunSession.
#include <gtest/gtest.h>

#include <string>

#include "engine/io/checkpoint.hpp"
#include "engine/session/run_session.hpp"
#include "engine/threads.hpp"
#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

TEST(GuiTeam, AnAdaptiveTeamGivesTheBitsOfOneThread) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run not found (Debian: apt-get install xvfb)";
  const auto dir = fresh_dir("team");
  const auto scene = write_small_drum(dir, "verlet:m2");
  const auto ck = dir / "final.h5";
  // 25 frames of 10 steps: two whole windows of 100 steps, the first on 2 threads, the second on 1.
  const GuiRun r = run_gui(scene.string() +
                               " --settle-time 0 --method verlet:m2 --threads 2 --frames 25 "
                               "--steps-per-frame 10 --checkpoint " +
                               ck.string(),
                           true);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string head = "team              adaptive: 2 thread(s) in ";
  const auto at = r.output.find(head);
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string report = r.output.substr(at);
  EXPECT_GE(std::stoul(report.substr(head.size())), 1u) << report;
  EXPECT_GE(std::stoul(report.substr(report.find(", 1 in ") + 7)), 1u) << report;
  const Checkpoint gui = read_checkpoint(ck);

  set_thread_count(1);
  SessionOptions o;
  o.scene_file = scene.string();
  o.method = "verlet:m2";
  o.settle_time = 0.0;
  RunSession session(load_dynamic_scene(scene.string()), o);
  session.settle();
  session.advance(250);
  const Particles& p = session.simulation().particles();
  EXPECT_EQ(gui.state.steps, session.simulation().steps());
  ASSERT_EQ(gui.state.particles.size(), p.size());
  EXPECT_EQ(differing_motion(gui.state.particles, p), 0u)
      << "position/velocity/omega components that differ in any bit";
}

}  // namespace
}  // namespace drumlab::test
