#pragma once
// `drumlab bench skips`: the speed each skip of engine/scene/scene_features.hpp gains, measured on
// a scene's rolling state against the general path that gives the same physics:
//   friction 0 (no tangential history, no rotation)  vs  friction = tiny (history path taken)
//   rolling_friction 0                               vs  rolling_friction = tiny
//   2D grid m2 on a shallow drum                     vs  3D grids m3 and m5
//   periodic ends (no end-cap contacts)              vs  caps: different physics, wall phase only
//   no output writers                                vs  --vtu and --h5 writers every K steps
// Each pair starts from the same state; the position difference after the run is printed (round
// off for the same physics). Median over repeats of the CPU time per step (one thread; the wall
// clock beside it); table on stdout, CSV + PNG bar chart.
#include <cstdint>
#include <string>

#include "app/bench/bench_state.hpp"

namespace drumlab::bench {

struct SkipsBenchOptions {
  std::string scene;              ///< scene file (default: the demo drum)
  std::uint64_t steps = 200;      ///< timed steps per run
  int repeats = 3;                ///< runs per variant; the median is reported
  std::uint64_t every = 0;        ///< writer cadence in steps (0: steps / 10)
  double tiny = 1e-100;           ///< the "tiny" coefficient that forces a general path
  std::string out = "out/bench";  ///< CSV + PNG folder
  RollingPlan plan;
};

/// Runs the benchmark; throws InputError for bad input (scene, output folder).
void run_bench_skips(const SkipsBenchOptions& opt);

}  // namespace drumlab::bench
