#pragma once
// `drumlab bench accuracy`: sweeps the knobs that trade speed for accuracy and measures both in
// one run. Each knob is one row of a table of sweeps (bench_accuracy.cpp, kSweeps): a name, its
// values and how a value changes the RunSettings; every other knob stays at the baseline (dt =
// 0.2 Rayleigh times, the scene's search method). For every setting:
// * binary collisions (analytic): |e_achieved - e| / e and |t_c - t_Hertz| / t_Hertz;
// * energy drift of an elastic frictionless system (exact: 0);
// * drum observables of the scene's steady rolling state, time-averaged over a window, against
//   the sweep's reference setting (the first value: smallest dt, brute search where it is
//   affordable): angle of repose, mean kinetic energy, flowing-layer thickness (relative errors),
//   centre of mass (distance / drum radius), and the largest particle displacement between the
//   two final states (trajectory deviation / smallest radius);
// * run time: wall time of the drum run per simulated second.
// Output: printed table, OUT/accuracy_<scene>.csv, OUT/accuracy_<scene>.png (error against run
// time, log-log, one curve per knob, the Pareto front over all settings marked).
#include <string>

#include "app/bench/bench_state.hpp"

namespace drumlab::bench {

struct AccuracyOptions {
  std::string scene;  ///< default: scenes/accuracy_drum.toml (--quick: scenes/accuracy_quick.toml)
  std::string out = "out/bench";
  bool quick = false;  ///< short windows (and the small quick scene unless --scene is given)
  RollingPlan plan = accuracy_plan();  ///< how the steady state is prepared and cached

  /// A steady rolling flow before the sweep: half a revolution after settling.
  static RollingPlan accuracy_plan() {
    RollingPlan p;
    p.turn_revolutions = 0.5;
    return p;
  }
};

/// Drum revolutions before the sweep with --quick (unless --turn is given).
inline constexpr double kAccuracyQuickTurnRevolutions = 0.2;

/// Runs the sweep; throws InputError for bad input (scene, output folder).
void run_bench_accuracy(AccuracyOptions opt);

/// Brute force is swept only on scenes with at most this many particles (O(N^2) per step).
inline constexpr std::size_t kAccuracyBruteMaxParticles = 1000;

}  // namespace drumlab::bench
