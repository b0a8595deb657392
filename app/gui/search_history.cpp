#include "app/gui/search_history.hpp"

#include <algorithm>

namespace drumlab::gui {

void History::add(double v, std::size_t keep) {
  values.push_back(static_cast<float>(v));
  while (values.size() > keep) values.pop_front();
}

void SearchHistory::add(const FrameSnapshot& s) {
  if (s.steps == last_step_) return;
  last_step_ = s.steps;
  const double n = std::max<double>(1.0, static_cast<double>(s.size()));
  cells_per_particle.add(static_cast<double>(s.counters.cells_visited) / n);
  tests_per_particle.add(static_cast<double>(s.counters.pairs_tested) / n);
  contacts_per_particle.add(static_cast<double>(s.counters.pairs_found) / n);
  if (s.diagnostics) kinetic.add(s.diagnostics->kinetic_energy);
  if (s.steps > last_timer_steps_) {
    const double steps = static_cast<double>(s.steps - last_timer_steps_);
    recent_split.search = s.timers.search - last_timers_.search;
    recent_split.forces = s.timers.forces - last_timers_.forces;
    recent_split.walls = s.timers.walls - last_timers_.walls;
    recent_split.integration = s.timers.integration - last_timers_.integration;
    recent_split.reorder = s.timers.reorder - last_timers_.reorder;
    if (last_timer_steps_ > 0) step_ms.add(1000.0 * recent_split.total() / steps);
  }
  last_timers_ = s.timers;
  last_timer_steps_ = s.steps;
}

}  // namespace drumlab::gui
