#pragma once
// `drumlab bench roofline`: per phase of the step (search, pair forces, walls, integration,
// re-ordering), the work done (roofline_model.hpp: flops, divisions and square roots, bytes,
// counted from the code and the run's counts), the rates achieved, their share of what one core
// can do (machine_limits.hpp, measured first) and what bounds the phase: compute, division and
// square root, cache or memory bandwidth, or latency (well below every roof). Table on stdout,
// CSV in the output folder.
#include <cstdint>
#include <string>

#include "app/bench/bench_state.hpp"
#include "app/bench/roofline_model.hpp"
#include "engine/session/phase_meter.hpp"

namespace drumlab::bench {

struct RooflineOptions {
  std::string scene;   ///< scene file (default: the demo drum)
  std::string method;  ///< search method; empty: the scene's (auto resolved)
  int threads = 1;     ///< OpenMP threads of the run (the roofs are one core's: x threads)
  std::uint64_t steps = 500;
  std::uint64_t warmup = 20;
  bool quick = false;  ///< short machine measurements (tests)
  std::string out = "out/bench";
  RollingPlan plan;
};

/// Runs it; throws InputError for bad input (scene, method, output folder).
void run_bench_roofline(const RooflineOptions& opt);

/// Advances `sim` `steps` steps and returns the counts the work model takes (roofline_model.hpp):
/// the step's own StepWork, the search's tests and builds, and the live bridges (sampled at five
/// points, as the engine does not sum them per step). `phase`, if given, gets the phase timers.
RunCounts count_run(Simulation& sim, std::uint64_t steps, PhaseStats* phase = nullptr);

}  // namespace drumlab::bench
