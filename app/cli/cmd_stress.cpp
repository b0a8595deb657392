// drumlab stress [--out DIR] [--quick] [--only TEXT]: a suite that tries to break the engine and
// prints, per case, what it used, the outcome it expects, the outcome it observed and pass/fail;
// also DIR/stress.csv. Exits non-zero (1) if any case misbehaves. `--quick` runs the cheap cases
// (the ctest label `stress` runs it); the full suite adds longer flows and a >= 1e8
// particle-step run.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "app/bench/stress_suite.hpp"
#include "app/cli/commands.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/threads.hpp"
#include "engine/types.hpp"

namespace drumlab::cli {

namespace {

struct StressRow {
  std::string name;
  std::string setup;
  std::string expected;
  bench::StressOutcome outcome;
  double seconds = 0.0;
};

std::string csv_field(const std::string& s) {
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void write_csv(const std::filesystem::path& file, const std::vector<StressRow>& rows) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "case,setup,expected,observed,pass,seconds\n";
    for (const StressRow& r : rows) {
      out << fmt::format("{},{},{},{},{},{:.3f}\n", csv_field(r.name), csv_field(r.setup),
                         csv_field(r.expected), csv_field(r.outcome.observed),
                         r.outcome.pass ? 1 : 0, r.seconds);
    }
  });
}

struct StressArgs {
  std::string out = "out/stress";
  bool quick = false;
  std::string only;
  int threads = 1;
};

void run_stress(const StressArgs& a) {
  const std::filesystem::path out(a.out);
  std::error_code ec;
  std::filesystem::create_directories(out / "work", ec);
  if (ec || !std::filesystem::is_directory(out / "work")) {
    throw InputError(fmt::format("--out {}: cannot create the folder ({})", a.out, ec.message()));
  }
  // One thread by default: the cases are small, and OpenMP threads that spin-wait on a loaded
  // machine slow a run down many times.
  set_thread_count(a.threads);
  bench::StressContext ctx;
  ctx.work = std::filesystem::absolute(out / "work");
  ctx.quick = a.quick;
  std::vector<bench::StressCase> cases = bench::physics_stress_cases(ctx);
  for (bench::StressCase& c : bench::cli_stress_cases(ctx)) cases.push_back(std::move(c));
  fmt::print("drumlab stress ({} suite)\n", a.quick ? "quick" : "full");
  fmt::print("| case | used | expected | observed | result | s |\n|---|---|---|---|---|---|\n");
  std::vector<StressRow> rows;
  for (bench::StressCase& c : cases) {
    if (!a.only.empty() && c.name.find(a.only) == std::string::npos) continue;
    const auto t0 = std::chrono::steady_clock::now();
    StressRow row{c.name, c.setup, c.expected, c.run(), 0.0};
    row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    fmt::print("| {} | {} | {} | {} | {} | {:.1f} |\n", row.name, row.setup, row.expected,
               row.outcome.observed, row.outcome.pass ? "pass" : "FAIL", row.seconds);
    std::fflush(stdout);
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw InputError(fmt::format("--only {}: no case matches", a.only));
  write_csv(out / "stress.csv", rows);
  std::size_t failed = 0;
  for (const StressRow& r : rows) failed += r.outcome.pass ? 0 : 1;
  fmt::print("{} of {} cases pass; table in {}\n", rows.size() - failed, rows.size(),
             (out / "stress.csv").string());
  if (failed > 0) {
    throw std::runtime_error(fmt::format("{} of {} stress cases misbehaved", failed, rows.size()));
  }
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
