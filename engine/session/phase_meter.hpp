#pragma once
// What a phase of a run cost: the differences of the simulation's running totals (steps, step
// timers, search counters) and of the wall and process CPU clocks between two moments.
#include <chrono>
#include <cstdint>
#include <ctime>

#include "engine/simulation.hpp"

namespace drumlab {

struct PhaseStats {
  std::uint64_t steps = 0;
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;     ///< process CPU time, all threads
  double output_seconds = 0.0;  ///< spent in observers (rendering, writers), not stepping
  StepTimers timers;
  SearchCounters search;
  StepWork work;
};

/// Takes the totals now; `finish` turns them into the phase's differences.
class PhaseMeter {
 public:
  explicit PhaseMeter(const Simulation& sim);
  PhaseStats finish() const;

 private:
  const Simulation& sim_;
  std::uint64_t steps0_;
  StepTimers timers0_;
  SearchCounters search0_;
  StepWork work0_;
  std::chrono::steady_clock::time_point start_;
  std::clock_t cpu_start_;
};

}  // namespace drumlab
