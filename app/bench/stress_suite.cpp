// `drumlab stress`: runs the cases of stress_suite.hpp, prints per case what it used, the outcome
// it expects, the outcome it observed and pass/fail, and writes OUT/stress.csv.
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>

#include <fmt/format.h>

#include "app/bench/stress_suite.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/types.hpp"

namespace drumlab::bench {

namespace {

struct StressRow {
  std::string name;
  std::string setup;
  std::string expected;
  StressOutcome outcome;
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

/// The case's outcome; a case that throws (a folder it cannot make, a file it cannot read)
/// misbehaves like any other: its row says what it threw, and the suite goes on.
StressOutcome run_case(const StressCase& c) {
  try {
    return c.run();
  } catch (const std::exception& e) {
    return {fmt::format("threw: {}", e.what()), false};
  }
}

}  // namespace

void run_stress_suite(const StressSuiteOptions& a) {
  const std::filesystem::path out(a.out);
  std::error_code ec;
  std::filesystem::create_directories(out / "work", ec);
  if (ec || !std::filesystem::is_directory(out / "work")) {
    throw InputError(fmt::format("--out {}: cannot create the folder ({})", a.out, ec.message()));
  }
  StressContext ctx;
  ctx.work = std::filesystem::absolute(out / "work");
  ctx.quick = a.quick;
  std::vector<StressCase> cases = physics_stress_cases(ctx);
  for (StressCase& c : cli_stress_cases(ctx)) cases.push_back(std::move(c));
  fmt::print("drumlab stress ({} suite)\n", a.quick ? "quick" : "full");
  fmt::print("| case | used | expected | observed | result | s |\n|---|---|---|---|---|---|\n");
  std::vector<StressRow> rows;
  for (StressCase& c : cases) {
    if (!a.only.empty() && c.name.find(a.only) == std::string::npos) continue;
    const auto t0 = std::chrono::steady_clock::now();
    StressRow row{c.name, c.setup, c.expected, run_case(c), 0.0};
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

}  // namespace drumlab::bench
