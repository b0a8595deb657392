#pragma once
// What `drumlab run` and `drumlab-mpi run` print around a RunSession: the session's choices, the
// plan, progress bars, and the summary of the turning phase. One code for both executables: the
// MPI run fills the same RunSummary with numbers over all ranks and prints it on rank 0. Reads
// the simulation between steps; never changes it.
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "engine/session/phase_meter.hpp"
#include "engine/session/run_session.hpp"
#include "engine/simulation.hpp"
#include "engine/spray/droplet_cloud.hpp"

namespace drumlab::cli {

/// A one-line progress bar on stderr (only when it is a terminal): steps/s and ETA.
class ProgressBar {
 public:
  ProgressBar(std::string label, std::uint64_t total_steps, bool shown = true);
  void update(std::uint64_t done);
  void finish();

 private:
  std::string label_;
  std::uint64_t total_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
};

/// Runs the session's settling steps (`steps`, from its plan; none: nothing) with a progress bar
/// (where `shown`).
void settle_with_progress(RunSession& session, std::uint64_t steps, bool shown = true);

/// Prints the search "auto" chose and why ("search auto       -> METHOD: REASON").
void print_auto_choice(const SearchChoice& choice);

/// Prints how the session resolved "auto" and what a restart read (the notes and the restart
/// line), as `run` does.
void print_session_choices(const RunSession& session);

/// The numbers of the turning phase's summary. A decomposed run's are over all ranks: the
/// particles of the whole run, search counters summed, the step timers' mean, the slowest rank's
/// wall and output seconds; the diagnostics are reduced by the simulation itself.
struct RunSummary {
  std::uint64_t particles = 0;
  PhaseStats phase;
  double dt = 0.0, rayleigh_time = 0.0, time = 0.0;
  std::string method, method_description, search_detail;
  Diagnostics diagnostics;           ///< at the end of the phase
  std::optional<SprayTotals> spray;  ///< a scene with [[spray]]: its liquid accounting
  /// A planetary drum ([drum.orbit]): the carrier's field now, Omega^2 R_o (m/s^2), and its ratio
  /// to gravity.
  std::optional<double> carrier_field;
  double carrier_field_in_g = 0.0;
};

/// The summary of `phase` of `sim` (`particles`: of the whole run). Calls sim.diagnostics(),
/// which is collective in a decomposed run.
RunSummary run_summary(const Simulation& sim, const PhaseStats& phase, std::uint64_t particles);

/// Prints the summary of a phase: throughput as "... particle-steps/s", the time split, search
/// counters per particle and step, energies and health.
void print_summary(const RunSummary& s);

/// Prints the plan, settles and turns the drum (frames for `observers` every `every` steps and on
/// their own schedules) with progress bars, then "-- turning phase --". Prints only where `print`
/// (rank 0 of a decomposed run, whose ranks all call it).
TurnResult settle_and_turn(RunSession& session, std::uint64_t every,
                           std::span<FrameObserver* const> observers, bool print);

/// Prints the adaptive team's line (nothing without a team).
void print_team(const RunSession& session);

}  // namespace drumlab::cli
