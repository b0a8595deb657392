// A method switched at step K (--switch-at K:METHOD) happens at exactly that step. Every method
// gives the same bits, so the particles alone cannot tell when it happened; the search's work
// can: each method tests its own candidate pairs, so the search counters summed since the start
// (and the last step's, and the method's name in each snapshot) follow a headless RunSession
// that switches at K, and differ from one that switches a step earlier or later. Checked inside
// drumlab-gui (its headless search line, and the bits of its checkpoint) and on the SimThread
// itself, snapshot by snapshot.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "app/gui/sim_thread.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/session/run_session.hpp"
#include "tests/gui/gui_test_helpers.hpp"

namespace drumlab::test {
namespace {

constexpr std::uint64_t kSwitchAt = 25;  // inside the third chunk of 10 steps
constexpr std::uint64_t kSteps = 60;
constexpr double kSettleTime = 0.02;

/// A headless run of the scene after its settling, switching from m5 to verlet:m2 after `at`
/// turning steps: after each turning step k (0: none yet), the search's name, its last step's
/// counters and its totals since the start.
struct HeadlessRun {
  std::uint64_t settle_steps = 0;
  std::vector<std::string> method;
  std::vector<SearchCounters> last, totals;
};

HeadlessRun headless_run(const std::string& scene, std::uint64_t at) {
  SessionOptions o;
  o.scene_file = scene;
  o.method = "m5";
  o.settle_time = kSettleTime;
  RunSession session(load_dynamic_scene(scene), o);
  session.settle();
  HeadlessRun r;
  r.settle_steps = session.simulation().steps();
  for (std::uint64_t k = 0; k <= kSteps; ++k) {
    if (k > 0) session.advance(1);
    if (k == at) session.set_search_method("verlet:m2");
    const Simulation& sim = session.simulation();
    r.method.push_back(std::string(sim.search().name()));
    r.last.push_back(sim.search().counters());
    r.totals.push_back(sim.search_totals());
  }
  return r;
}

std::string line(const SearchCounters& c) {
  return std::to_string(c.cells_visited) + " cells visited, " + std::to_string(c.pairs_tested) +
         " pairs tested, " + std::to_string(c.pairs_found) + " found";
}

bool same(const SearchCounters& a, const SearchCounters& b) {
  return a.cells_visited == b.cells_visited && a.pairs_tested == b.pairs_tested &&
         a.pairs_found == b.pairs_found;
}

/// The oracle, and a check that it can tell the scheduled step from its neighbours.
HeadlessRun oracle(const std::string& scene) {
  HeadlessRun at = headless_run(scene, kSwitchAt);
  for (const std::uint64_t other : {kSwitchAt - 1, kSwitchAt + 1}) {
    const HeadlessRun r = headless_run(scene, other);
    EXPECT_FALSE(same(r.totals.back(), at.totals.back()))
        << "a switch after " << other << " steps does the same search work as after " << kSwitchAt
        << ": the test could not tell them apart";
  }
  return at;
}

TEST(GuiSwitch, SwitchHappensAtTheScheduledStepInsideTheGui) {
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
  const HeadlessRun expected = oracle(scene.string());
  const std::string search_line =
      "search            verlet:m2; since the start: " + line(expected.totals.back());
  EXPECT_NE(r.output.find(search_line), std::string::npos)
      << "expected \"" << search_line << "\" in:\n"
      << r.output;

  const Checkpoint gui = read_checkpoint(ck);
  SessionOptions o;
  o.scene_file = scene.string();
  o.method = "m5";
  o.settle_time = kSettleTime;
  RunSession session(load_dynamic_scene(scene.string()), o);
  session.settle();
  session.advance(kSwitchAt);
  session.set_search_method("verlet:m2");
  session.advance(kSteps - kSwitchAt);
  const Simulation& sim = session.simulation();
  EXPECT_EQ(gui.state.steps, sim.steps());
  EXPECT_EQ(gui.state.search_method, "verlet:m2");
  ASSERT_EQ(gui.state.particles.size(), sim.particles().size());
  EXPECT_EQ(differing_motion(gui.state.particles, sim.particles()), 0u)
      << "position/velocity/omega components that differ in any bit";
}

TEST(GuiSwitch, EverySnapshotShowsTheSearchOfItsStep) {
  const auto dir = fresh_dir("switch-thread");
  const auto scene = write_small_drum(dir, "m5");
  const HeadlessRun expected = oracle(scene.string());
  SessionOptions o;
  o.scene_file = scene.string();
  o.method = "m5";
  o.settle_time = kSettleTime;
  gui::SimThread sim(load_dynamic_scene(scene.string()), o, {}, 1,
                     gui::ScheduledSwitch{kSwitchAt, "verlet:m2"}, kSteps);
  sim.set_chunk(10);
  // Paused, one chunk at a time (a settling chunk, then up to 10 turning steps, cut at the
  // switch): each is followed by a snapshot, taken here before the next step.
  std::vector<std::shared_ptr<const FrameSnapshot>> seen;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!sim.finished() && std::chrono::steady_clock::now() < deadline) {
    const std::uint64_t before = sim.generation();
    sim.single_step();
    while (sim.generation() == before && !sim.finished()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    seen.push_back(sim.latest());
  }
  ASSERT_EQ(sim.state_text(), "done");
  ASSERT_FALSE(seen.empty());
  std::size_t turning = 0, after_switch = 0;
  for (const auto& s : seen) {
    ASSERT_NE(s, nullptr);
    if (s->steps < expected.settle_steps) continue;  // the settling's
    const std::uint64_t k = s->steps - expected.settle_steps;
    ASSERT_LE(k, kSteps);
    ++turning;
    after_switch += k >= kSwitchAt;
    EXPECT_EQ(s->search_name, expected.method[k]) << "after " << k << " turning steps";
    EXPECT_TRUE(same(s->counters, expected.last[k]))
        << "after " << k << " turning steps: " << line(s->counters) << ", expected "
        << line(expected.last[k]);
    EXPECT_TRUE(same(s->totals, expected.totals[k]))
        << "after " << k << " turning steps: " << line(s->totals) << ", expected "
        << line(expected.totals[k]);
  }
  EXPECT_EQ(seen.back()->steps, expected.settle_steps + kSteps);
  EXPECT_GE(turning, 7u) << "snapshots after 0, 10, 20, 25, 35, 45, 55 and 60 turning steps";
  EXPECT_GE(after_switch, 4u);
}

}  // namespace
}  // namespace drumlab::test
