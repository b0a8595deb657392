#pragma once
// `drumlab bench regimes`: the drum regime map. For each Froude number the settled bed of a drum
// (default scenes/regime_drum.toml, the demo drum scaled down) is turned at omega = sqrt(Fr g / R):
// first a transient (the bed is lifted from rest to its dynamic state), then a window in which the
// drum observables (engine/analysis/drum_observables.hpp) are sampled and the regime classified
// (engine/analysis/flow_regime.hpp). Printed beside the regime predicted from Fr; CSV + PNG chart
// of the dynamic angle of repose against Fr.
#include <cstdint>
#include <string>
#include <vector>

#include "app/cli/bench_state.hpp"

namespace drumlab::cli {

struct RegimesBenchOptions {
  std::string scene;           ///< scene file (default: scenes/regime_drum.toml)
  std::vector<double> froude;  ///< empty: 1e-4 ... 1 (quick: 1e-3, 1e-2, 0.1, 1)
  bool quick = false;          ///< shorter transient and window, fewer Froude numbers
  double column_width = 0.0;   ///< surface column width, m (0: the observables' default)
  std::string out = "out/bench";
  RollingPlan plan;  ///< settling only (turn_revolutions = 0)
};

/// Drum turn (rad) and least simulated time (s) of the transient and of the window.
struct RegimeWindow {
  double transient_rad = 0.8;
  double transient_min_s = 1.0;
  double window_rad = 0.8;
  double window_min_s = 1.0;
  int samples = 40;
};

/// Runs the sweep; throws InputError for bad input (scene, Froude number, output folder).
void run_bench_regimes(const RegimesBenchOptions& opt);

}  // namespace drumlab::cli
