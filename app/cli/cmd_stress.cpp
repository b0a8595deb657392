// drumlab stress [--out DIR] [--quick] [--only TEXT]: a suite that tries to break the engine and
// prints, per case, what it used, the outcome it expects, the outcome it observed and pass/fail;
// also DIR/stress.csv. Exits non-zero (1) if any case misbehaves. `--quick` runs the cheap cases
// (the ctest label `stress` runs it); the full suite adds longer flows and a >= 1e8
// particle-step run.
#include <memory>
#include <string>

#include "app/bench/stress_suite.hpp"
#include "app/cli/commands.hpp"
#include "engine/threads.hpp"

namespace drumlab::cli {

namespace {

struct StressArgs {
  std::string out = "out/stress";
  bool quick = false;
  std::string only;
  int threads = 1;
};

void run_stress(const StressArgs& a) {
  // One thread by default: the cases are small, and OpenMP threads that spin-wait on a loaded
  // machine slow a run down many times.
  set_thread_count(a.threads);
  bench::run_stress_suite({a.out, a.quick, a.only});
}

}  // namespace

void add_stress_command(CLI::App& app) {
  auto a = std::make_shared<StressArgs>();
  CLI::App* cmd = app.add_subcommand(
      "stress", "Try to break the engine: unstable dt, extreme drums, bad inputs; table + CSV");
  cmd->add_option("--out", a->out, "folder for stress.csv and the cases' files (out/stress)");
  cmd->add_flag("--quick", a->quick, "only the cheap cases (what ctest -L stress runs)");
  cmd->add_option("--only", a->only, "run only the cases whose name contains TEXT");
  cmd->add_option("--threads", a->threads, "OpenMP threads of the in-process cases (1)")
      ->check(CLI::Range(1, 1024));
  cmd->callback([a] { run_stress(*a); });
}

}  // namespace drumlab::cli
