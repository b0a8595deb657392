#pragma once
// Progress bar and end-of-run summary for `drumlab run` / `drumlab demo`. Reads the simulation
// between steps; never changes it.
#include <chrono>
#include <cstdint>
#include <ctime>
#include <string>

#include "engine/session/phase_meter.hpp"
#include "engine/session/run_session.hpp"
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

/// Runs the session's settling steps (`steps`, from its plan; none: nothing) with a progress bar.
void settle_with_progress(RunSession& session, std::uint64_t steps);

/// Prints the summary of a phase: throughput as "... particle-steps/s", the time split, search
/// counters per particle and step, energies and health.
void print_summary(const Simulation& sim, const PhaseStats& phase);

}  // namespace drumlab::cli
