#pragma once
// The search's history for the Search panel's plots: cells, tests and contacts per particle,
// kinetic energy and time per step, one value per new snapshot, and how the recent steps' time
// splits between the parts of a step.
#include <cstddef>
#include <cstdint>
#include <deque>

#include "engine/session/frame_snapshot.hpp"

namespace drumlab::gui {

/// A bounded series for a history plot.
struct History {
  std::deque<float> values;
  void add(double v, std::size_t keep = 300);
};

struct SearchHistory {
  History cells_per_particle, tests_per_particle, contacts_per_particle, kinetic, step_ms;
  StepTimers recent_split;  ///< the step time's parts since the previous snapshot

  /// Adds `s` (once per step count).
  void add(const FrameSnapshot& s);

 private:
  std::uint64_t last_step_ = 0;
  StepTimers last_timers_;
  std::uint64_t last_timer_steps_ = 0;
};

}  // namespace drumlab::gui
