#include "engine/session/phase_meter.hpp"

namespace drumlab {

PhaseMeter::PhaseMeter(const Simulation& sim)
    : sim_(sim),
      steps0_(sim.steps()),
      timers0_(sim.timers()),
      search0_(sim.search_totals()),
      work0_(sim.work()),
      start_(std::chrono::steady_clock::now()),
      cpu_start_(std::clock()) {}

PhaseStats PhaseMeter::finish() const {
  PhaseStats s;
  s.steps = sim_.steps() - steps0_;
  s.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  s.cpu_seconds = static_cast<double>(std::clock() - cpu_start_) / CLOCKS_PER_SEC;
  const StepTimers& t = sim_.timers();
  s.timers = {t.search - timers0_.search,   t.forces - timers0_.forces,
              t.walls - timers0_.walls,     t.integration - timers0_.integration,
              t.reorder - timers0_.reorder, t.spray - timers0_.spray};
  const SearchCounters& c = sim_.search_totals();
  s.search = {c.cells_visited - search0_.cells_visited, c.pairs_tested - search0_.pairs_tested,
              c.pairs_found - search0_.pairs_found, c.cells_total};
  const StepWork& w = sim_.work();
  s.work = {w.particles - work0_.particles,
            w.listed_pairs - work0_.listed_pairs,
            w.touching_pairs - work0_.touching_pairs,
            w.wall_candidates - work0_.wall_candidates,
            w.reorders - work0_.reorders,
            w.wall_contacts - work0_.wall_contacts};
  return s;
}

}  // namespace drumlab
