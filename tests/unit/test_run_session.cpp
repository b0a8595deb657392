// RunSession (engine/session/run_session.hpp): the plan, settling with the drum at rest, frames
// at the start of the turn and every K steps, a progress callback that can stop a phase, "auto"
// resolved as data, and the same trajectory as driving the Simulation by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/fill/file_fill.hpp"
#include "engine/session/run_session.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab {
namespace {

SceneConfig small_scene() {
  return parse_scene(test::small_drum_scene(), "small.toml");
}

class CountingObserver final : public FrameObserver {
 public:
  void on_frame(const Simulation& sim, std::uint64_t frame) override {
    frames.push_back(frame);
    steps.push_back(sim.steps());
  }
  void on_finish(const Simulation&) override { ++finished; }
  std::uint64_t every() const override { return own_every; }
  std::vector<std::uint64_t> frames, steps;
  int finished = 0;
  std::uint64_t own_every = 0;
};

TEST(RunSession, PlansSettlesAndTurnsWithFrames) {
  const SceneConfig scene = small_scene();
  SessionOptions options;
  options.scene_file = "small.toml";
  RunSession session(scene, options);
  const SessionPlan plan = session.plan();
  const double dt = session.simulation().dt();
  EXPECT_EQ(plan.settle_steps, static_cast<std::uint64_t>(std::ceil(0.01 / dt)));
  EXPECT_EQ(plan.turn_steps, static_cast<std::uint64_t>(std::ceil(0.01 / dt)));
  session.settle();
  EXPECT_EQ(session.simulation().steps(), plan.settle_steps);
  EXPECT_EQ(session.simulation().drum_omega(), scene.drum.omega);
  CountingObserver o;
  FrameObserver* observers[] = {&o};
  const TurnResult r = session.run_turn(50, 20, observers);
  EXPECT_EQ(r.stats.steps, 50u);
  EXPECT_FALSE(r.stopped);
  EXPECT_EQ(r.frames, 3u);  // at the start, after 20 and 40 steps
  EXPECT_EQ(o.frames, (std::vector<std::uint64_t>{0, 1, 2}));
  EXPECT_EQ(o.steps, (std::vector<std::uint64_t>{plan.settle_steps, plan.settle_steps + 20,
                                                 plan.settle_steps + 40}));
  EXPECT_EQ(o.finished, 1);
}

// An observer with a schedule of its own (a checkpoint every K steps) sees its frames at the
// multiples of K, the others at the run's; the chunks of steps end at both.
TEST(RunSession, ObserverWithItsOwnScheduleSeesItsOwnFrames) {
  RunSession session(small_scene(), SessionOptions{});
  const std::uint64_t start = session.simulation().steps();
  CountingObserver run, own;
  own.own_every = 15;
  FrameObserver* observers[] = {&run, &own};
  const TurnResult r = session.run_turn(50, 20, observers);
  EXPECT_EQ(r.stats.steps, 50u);
  EXPECT_EQ(run.steps, (std::vector<std::uint64_t>{start, start + 20, start + 40}));
  EXPECT_EQ(own.steps, (std::vector<std::uint64_t>{start, start + 15, start + 30, start + 45}));
  EXPECT_EQ(own.frames, (std::vector<std::uint64_t>{0, 1, 2, 3}));
  EXPECT_EQ(run.finished, 1);
  EXPECT_EQ(own.finished, 1);
}

TEST(RunSession, SameTrajectoryAsTheSimulationDrivenByHand) {
  const SceneConfig scene = small_scene();
  RunSession session(scene, SessionOptions{});
  session.settle();
  session.advance(30);
  Simulation by_hand(scene, initial_fill(scene));
  by_hand.set_drum_omega(0.0);
  by_hand.advance(session.settle_steps());
  by_hand.set_drum_omega(scene.drum.omega);
  by_hand.advance(30);
  EXPECT_EQ(session.simulation().particles().position, by_hand.particles().position);
  EXPECT_EQ(session.simulation().particles().velocity, by_hand.particles().velocity);
}

TEST(RunSession, ProgressCanStopAPhase) {
  RunSession session(small_scene(), SessionOptions{});
  std::vector<std::uint64_t> seen;
  const std::uint64_t done = session.advance(100, [&](std::uint64_t d, std::uint64_t total) {
    seen.push_back(d);
    EXPECT_EQ(total, 100u);
    return d < 40;
  });
  EXPECT_EQ(done, 40u);  // chunks of output.diagnostics_every = 20
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{20, 40}));
  EXPECT_EQ(session.simulation().steps(), 40u);
}

TEST(RunSession, AutoIsResolvedAsDataAndSwitchableBetweenSteps) {
  SessionOptions options;
  options.method = "auto";
  RunSession session(small_scene(), options);
  ASSERT_TRUE(session.auto_choice().has_value());
  EXPECT_EQ(session.scene().search_method, session.auto_choice()->method);
  EXPECT_EQ(session.simulation().scene().search_method, session.auto_choice()->method);
  EXPECT_FALSE(session.auto_choice()->reason.empty());
  session.advance(5);
  session.set_search_method("m2");
  EXPECT_EQ(session.simulation().search().name(), "m2");
  session.advance(5);
  EXPECT_EQ(session.simulation().steps(), 10u);
  EXPECT_THROW(session.set_search_method("m9"), InputError);
}

TEST(RunSession, PlanWithoutARunLengthNamesTheSceneFile) {
  SessionOptions options;
  options.scene_file = "short.toml";
  SceneConfig scene = small_scene();  // built in code: a loaded scene always names its length
  scene.time.duration.reset();
  scene.time.revolutions.reset();
  RunSession session(scene, options);
  try {
    session.plan();
    ADD_FAILURE() << "no run length accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("short.toml: time:"), std::string::npos) << e.what();
  }
  options.steps = 7;
  EXPECT_EQ(RunSession(scene, options).plan().turn_steps, 7u);
}

}  // namespace
}  // namespace drumlab
