#pragma once
// `drumlab bench regimes`: the drum regime map. For each Froude number the settled bed of a drum
// (default scenes/regime_drum.toml, the demo drum scaled down) is turned at omega = sqrt(Fr g / R):
// first a lift (the bed is raised from rest to a flowing state, at no less than the lift Froude
// number so that the slow drums do not spend most of their time on it), then a settle at the
// target omega (the flow adapts to it), then a window in which the drum observables
// (engine/analysis/drum_observables.hpp) are sampled and the regime classified
// (engine/analysis/flow_regime.hpp). Printed beside the regime predicted from Fr; CSV + PNG chart
// of the dynamic angle of repose against Fr (log Fr axis).
#include <cstdint>
#include <string>
#include <vector>

#include "app/bench/bench_state.hpp"

namespace drumlab::bench {

struct RegimesBenchOptions {
  std::string scene;           ///< scene file (default: scenes/regime_drum.toml)
  std::vector<double> froude;  ///< empty: 1e-4 ... 1 (quick: 1e-3, 1e-2, 0.1, 1)
  bool quick = false;          ///< shorter transient and window, fewer Froude numbers
  double column_width = 0.0;   ///< surface column width, m (0: the observables' default)
  std::string out = "out/bench";
  RollingPlan plan;  ///< settling only (turn_revolutions = 0)
};

/// Drum turn (rad) and least simulated time (s) of the phases run for each Froude number.
struct RegimeWindow {
  double lift_froude = 0.01;  ///< the lift turns the drum at max(Fr, lift_froude)
  double lift_rad = 0.7;
  double settle_rad = 0.1;  ///< at the target Fr
  double settle_min_s = 0.5;
  double window_rad = 0.5;  ///< the window: max(window_rad / omega, window_min_s)
  double window_min_s = 1.0;
  int samples = 60;
};

/// Runs the sweep; throws InputError for bad input (scene, Froude number, output folder).
void run_bench_regimes(const RegimesBenchOptions& opt);

}  // namespace drumlab::bench
