#pragma once
// `drumlab stress`: cases that try to break the engine. Each case states what it used, what it
// expects and what it observed, and whether the observation matches the expectation.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace drumlab::bench {

struct StressOutcome {
  std::string observed;
  bool pass = false;
};

struct StressCase {
  std::string name;
  std::string setup;     ///< what the case used (particles, steps, parameters)
  std::string expected;  ///< the outcome it asserts
  std::function<StressOutcome()> run;
};

struct StressContext {
  std::filesystem::path work;  ///< scratch folder for scenes, CSVs and outputs of the cases
  bool quick = false;          ///< the cheap subset (ctest label `stress`)
};

/// Drum flows over the regime map, size ratios, materials, friction, overlapping file packings,
/// and (full suite only) the long run: in-process through the Simulation API.
std::vector<StressCase> physics_stress_cases(const StressContext& ctx);
/// Time steps above the Rayleigh time and adversarial scenes/CSVs/outputs: through the `drumlab`
/// executable itself, asserting exit codes, one-line messages and the files left behind.
std::vector<StressCase> cli_stress_cases(const StressContext& ctx);

struct StressSuiteOptions {
  std::string out = "out/stress";  ///< folder for stress.csv and the cases' files (OUT/work)
  bool quick = false;              ///< the cheap cases only
  std::string only;                ///< non-empty: only the cases whose name contains it
};

/// Runs the suite: prints the table, writes OUT/stress.csv. Throws InputError for an unusable
/// folder or an `only` that matches no case, std::runtime_error (naming how many) if any case
/// misbehaves: its observation does not match its expectation, or it throws (its row says what).
void run_stress_suite(const StressSuiteOptions& opt);

}  // namespace drumlab::bench
