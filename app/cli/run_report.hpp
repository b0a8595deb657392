#pragma once
// Progress bar and end-of-run summary for `drumlab run` / `drumlab demo`. Reads the simulation
// between steps; never changes it.
#include <chrono>
#include <cstdint>
#include <ctime>
#include <string>

#include "engine/simulation.hpp"

namespace drumlab::cli {

/// A one-line progress bar on stderr (only when it is a terminal): steps/s and ETA.
class ProgressBar {
 public:
  ProgressBar(std::string label, std::uint64_t total_steps);
  void update(std::uint64_t done);
  void finish();

 private:
  std::string label_;
  std::uint64_t total_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
};

/// What a phase of the run cost: differences of the simulation's running totals.
struct PhaseStats {
  std::uint64_t steps = 0;
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;     ///< process CPU time, all threads
  double output_seconds = 0.0;  ///< spent in observers (rendering, writers), not stepping
  StepTimers timers;
  SearchCounters search;
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
  std::chrono::steady_clock::time_point start_;
  std::clock_t cpu_start_;
};

/// Prints the summary of a phase: throughput as "... particle-steps/s", the time split, search
/// counters per particle and step, energies and health.
void print_summary(const Simulation& sim, const PhaseStats& phase);

}  // namespace drumlab::cli
