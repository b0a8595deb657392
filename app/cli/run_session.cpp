#include "app/cli/run_session.hpp"

#include <fmt/format.h>

#include "app/cli/output_observers.hpp"
#include "app/run/output_schedule.hpp"
#include "engine/threads.hpp"

namespace drumlab::cli {

void run_session(const RunOptions& opt, std::span<FrameObserver* const> extra_observers) {
  const SceneConfig scene = load_dynamic_scene(opt.scene);
  check_run_options(opt, !extra_observers.empty());
  check_run_options_for(opt, scene);
  set_thread_count(opt.threads);
  const std::vector<std::unique_ptr<FrameObserver>> outputs = make_output_observers(opt);
  std::vector<FrameObserver*> observers(extra_observers.begin(), extra_observers.end());
  for (const auto& o : outputs) observers.push_back(o.get());
  RunSession session(scene, session_options(opt));
  print_session_choices(session);
  const bool frames_taken = !extra_observers.empty() || opt.frame_outputs();
  const std::uint64_t every = frame_every(opt, session.plan().turn_steps, frames_taken);
  const TurnResult turn = settle_and_turn(session, every, observers, true);
  const Simulation& sim = session.simulation();
  print_summary(run_summary(sim, turn.stats, sim.particles().size()));
  print_team(session);
}

}  // namespace drumlab::cli
