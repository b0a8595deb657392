// The adaptive OpenMP team (engine/session/team_chooser.hpp): which team runs after which
// timings, and that a run whose team changes between windows gives the same bits as one thread.
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/io/checkpoint.hpp"
#include "engine/session/team_chooser.hpp"
#include "tests/same_bits.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

constexpr std::uint64_t kWindow = TeamChooser::kWindowSteps;

// Runs one window with the chooser's team at `seconds_per_step`; returns the team it ran.
int window(TeamChooser& c, double seconds_per_step) {
  const int team = c.team();
  c.record(seconds_per_step * static_cast<double>(kWindow), kWindow);
  return team;
}

TEST(TeamChooser, TimesBothTeamsThenRunsTheFasterAndProbesTheOther) {
  TeamChooser c(2, 3);
  EXPECT_EQ(window(c, 1.0), 2);  // the full team first
  EXPECT_EQ(window(c, 0.5), 1);  // then one thread, faster: it runs
  for (int k = 0; k < 3; ++k) EXPECT_EQ(window(c, 0.5), 1);
  EXPECT_EQ(window(c, 0.3), 2);  // the probe: now the full team is faster
  EXPECT_EQ(c.team(), 2);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(window(c, 0.3), 2);
  EXPECT_EQ(window(c, 0.6), 1);  // probe: slower, the full team stays
  EXPECT_EQ(c.team(), 2);
  EXPECT_EQ(c.full_windows(), 1u + 1u + 3u);
  EXPECT_EQ(c.single_windows(), 1u + 3u + 1u);
}

// A probe that loses doubles the wait before the next, up to kMaxBackoff x probe_every; a change
// of team starts from probe_every again.
TEST(TeamChooser, WaitsLongerAfterEachLostProbeAndStartsAgainAfterAChange) {
  TeamChooser c(2, 2);
  EXPECT_EQ(window(c, 1.0), 2);
  EXPECT_EQ(window(c, 0.5), 1);  // timing one thread: it runs, no back-off yet
  EXPECT_EQ(c.probe_interval(), 2);
  for (const int wait : {2, 4, 8, 8}) {
    EXPECT_EQ(c.probe_interval(), wait);
    for (int k = 0; k < wait; ++k) EXPECT_EQ(window(c, 0.5), 1);
    EXPECT_EQ(window(c, 1.0), 2);  // the probe loses
    EXPECT_EQ(c.probe_interval(), std::min(2 * wait, TeamChooser::kMaxBackoff * 2));
  }
  for (int k = 0; k < 8; ++k) EXPECT_EQ(window(c, 0.5), 1);
  EXPECT_EQ(window(c, 0.2), 2);  // the probe wins: the full team runs, probes every 2 again
  EXPECT_EQ(c.probe_interval(), 2);
  EXPECT_EQ(window(c, 0.2), 2);
  EXPECT_EQ(window(c, 0.2), 2);
  EXPECT_EQ(window(c, 0.5), 1);  // its probe
}

TEST(TeamChooser, KeepsItsTeamWhenTheOtherIsFasterByLessThanTheMargin) {
  TeamChooser c(4, 2, 0.05);
  EXPECT_EQ(window(c, 1.0), 4);
  EXPECT_EQ(window(c, 0.97), 1);  // 3 % faster: not enough
  EXPECT_EQ(c.team(), 4);
}

TEST(TeamChooser, AWindowClosesOnlyOnceItHoldsEnoughSteps) {
  TeamChooser c(2);
  const std::uint64_t part = kWindow / 4 + 1;  // four parts close the window, three do not
  for (int k = 0; k < 3; ++k) c.record(1.0, part);
  EXPECT_EQ(c.team(), 2);
  EXPECT_EQ(c.full_windows(), 0u);
  c.record(1.0, part);
  EXPECT_EQ(c.full_windows(), 1u);
  EXPECT_EQ(c.team(), 1);  // the probe of one thread
}

TEST(TeamChooser, OneThreadAskedIsOneThreadAlways) {
  TeamChooser c(1);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(window(c, 1.0), 1);
  EXPECT_EQ(c.full_windows() + c.single_windows(), 0u);
}

// `drumlab run --threads 2` (adaptive, the other team timed after every window) runs windows on
// 2, 1, then alternately the faster and the other team: both changes, 2 -> 1 and 1 -> 2, happen
// in its 6 whole windows (650 steps). Its checkpoint must equal the one-thread run's bit for bit.
TEST(TeamChooser, ARunWhoseTeamChangesIsBitIdenticalToOneThread) {
  TempDir dir("team-chooser");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const std::string d = dir.path().string() + "/";
  const std::string steps = " --settle-time 0 --steps 650";
  auto r = run_cli("run " + scene + steps + " --threads 2 --team-probe-every 1 --checkpoint " + d +
                   "adaptive.h5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto line = r.output.find("team              adaptive: 2 thread(s) in ");
  ASSERT_NE(line, std::string::npos) << r.output;
  // 6 whole windows (the last 50 steps close none), at least 2 on each team
  const std::string report = r.output.substr(line);
  const auto full = std::stoul(report.substr(report.find(" in ") + 4));
  const auto one = std::stoul(report.substr(report.find(", 1 in ") + 7));
  EXPECT_EQ(full + one, 6u) << report;
  EXPECT_GE(full, 2u) << report;
  EXPECT_GE(one, 2u) << report;
  r = run_cli("run " + scene + steps + " --threads 1 --checkpoint " + d + "one.h5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("team    "), std::string::npos) << r.output;
  r = run_cli("run " + scene + steps + " --threads 2 --team fixed --checkpoint " + d + "fixed.h5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("team    "), std::string::npos) << r.output;
  const SimulationState a = read_checkpoint(d + "adaptive.h5").state;
  for (const char* other : {"one.h5", "fixed.h5"}) {
    const SimulationState b = read_checkpoint(d + other).state;
    EXPECT_EQ(a.steps, b.steps) << other;
    EXPECT_TRUE(same_bits(a.particles.position, b.particles.position)) << other;
    EXPECT_TRUE(same_bits(a.particles.velocity, b.particles.velocity)) << other;
    EXPECT_TRUE(same_bits(a.particles.omega, b.particles.omega)) << other;
    EXPECT_TRUE(same_bits(a.contact_history, b.contact_history)) << other;
  }
}

TEST(TeamChooser, AnUnknownTeamIsRefusedWithOneLine) {
  TempDir dir("team-chooser-bad");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const auto r = run_cli("run " + scene + " --steps 10 --team sometimes");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--team"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace drumlab::test
