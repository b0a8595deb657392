#pragma once
// `drumlab bench search`: every contact-search method on the flowing demo drum (the cached rolling
// state) and on the paper's packings: time per call (Verlet: build and visit apart), cells visited
// and pairs tested per particle, pairs tested per true contact, the step time of a short dynamic
// run (flowing state only) and the paper's operation estimate. Table, CSV + PNG chart.
#include <cstdint>
#include <string>
#include <vector>

#include "app/bench/bench_state.hpp"

namespace drumlab::bench {

struct SearchBenchOptions {
  std::string scene;                 ///< flowing scene (default: the demo drum)
  std::vector<std::string> methods;  ///< empty: every method (brute on the flowing state only)
  bool table1 = true;                ///< also the paper's Table 1 packing (192k particles)
  bool table2 = false;               ///< also the paper's Table 2 packing (2.6M particles)
  int repeats = 3;                   ///< timed calls per method after the first (median kept)
  std::uint64_t steps = 50;          ///< dynamic steps per method on the flowing state (0: none)
  std::string out = "out/bench";
  RollingPlan plan;
};

void run_bench_search(const SearchBenchOptions& opt);

}  // namespace drumlab::bench
