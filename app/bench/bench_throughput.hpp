#pragma once
// `drumlab bench throughput`: particle-steps per second of a scene's rolling state for each search
// method (and thread count), with the time split, search counters, Verlet rebuilds and patches,
// heap bytes per particle. Table on stdout, CSV + PNG bar chart in the output folder.
#include <cstdint>
#include <string>
#include <vector>

#include "app/bench/bench_state.hpp"

namespace drumlab::bench {

struct ThroughputOptions {
  std::string scene;                 ///< scene file (default: the demo drum)
  std::vector<std::string> methods;  ///< empty: every method except brute
  int threads = 1;                   ///< > 1: also run with this many OpenMP threads
  std::uint64_t steps = 500;         ///< timed steps per method
  std::uint64_t warmup = 20;         ///< untimed steps first (first Verlet build, caches)
  /// Particle re-ordering intervals to compare (performance.sort_every); empty: the scene's.
  std::vector<std::int64_t> sort_every;
  int repeats = 1;  ///< runs per row; the fastest is kept (a noisy machine only slows runs down)
  /// Also run each method on the same rolling state without the cohesive laws ([liquid],
  /// [cohesion]): rows "METHOD dry", the wet/dry cost ratio printed.
  bool dry_too = false;
  std::string out = "out/bench";  ///< CSV + PNG folder
  RollingPlan plan;
};

/// Runs the benchmark; throws InputError for bad input (scene, method, output folder).
void run_bench_throughput(const ThroughputOptions& opt);

/// Steps brute force runs at most (it is O(N^2) per step).
inline constexpr std::uint64_t kBruteMaxSteps = 20;

}  // namespace drumlab::bench
