// `bench accuracy --quick` (app/bench, in-process) end to end on the 300-particle quick drum (about
// 5 s): exit 0, one CSV row per setting, a PNG chart (when built with rendering), errors that fall
// as the time step falls (contact duration against Hertz theory at every step of the sweep, energy
// drift between the ends), and search methods whose trajectories coincide with brute force. A bad
// output folder gives exit code 2 (the command itself).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "app/bench/bench_accuracy.hpp"
#include "tests/unit/bench_runner.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

using CsvRow = std::map<std::string, std::string>;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::vector<CsvRow> read_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::vector<CsvRow> rows;
  if (!std::getline(in, line)) return rows;
  const auto header = split(line);
  while (std::getline(in, line)) {
    const auto cells = split(line);
    CsvRow row;
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
    rows.push_back(std::move(row));
  }
  return rows;
}

double number(const CsvRow& row, const std::string& key) {
  const auto it = row.find(key);
  return it == row.end() || it->second.empty() ? -1.0 : std::stod(it->second);
}

bool looks_like_png(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(8, '\0');
  return in.read(head.data(), 8) && head == "\x89PNG\r\n\x1a\n" &&
         std::filesystem::file_size(file) > 1000;
}

TEST(CliBenchAccuracy, QuickSweepWritesCsvAndChartAndErrorFallsWithDt) {
  TempDir dir("bench-accuracy");
  const auto out = dir.path() / "out";
  // As `drumlab bench accuracy --quick`.
  auto opt = bench_options<bench::AccuracyOptions>("", dir.path());
  opt.quick = true;
  opt.plan.turn_revolutions = bench::kAccuracyQuickTurnRevolutions;
  const auto r = run_bench([&] { bench::run_bench_accuracy(opt); });
  ASSERT_TRUE(r.ok) << r.output;
  EXPECT_NE(r.output.find("steady state"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("recommended dt"), std::string::npos) << r.output;
  const auto rows = read_csv(out / "accuracy_accuracy_quick.csv");
  // 6 time steps + 9 search methods (brute included) + 3 Verlet skins + 4 sort intervals.
  ASSERT_EQ(rows.size(), 22u) << r.output;
  if (r.output.find("built without rendering") == std::string::npos) {
    EXPECT_TRUE(looks_like_png(out / "accuracy_accuracy_quick.png"));
  }

  std::vector<CsvRow> dt_rows;
  for (const auto& row : rows) {
    if (row.at("knob") == "dt_factor") dt_rows.push_back(row);
  }
  ASSERT_EQ(dt_rows.size(), 6u);
  EXPECT_EQ(dt_rows.front().at("value"), "0.02");
  // The contact duration error against Hertz theory falls at every step from 0.4 t_R down to
  // 0.02 t_R (measured: 1.7e-2, 4.4e-3, 9.6e-4, 1.7e-4, 5.1e-5).
  for (std::size_t k = 0; k + 2 < dt_rows.size(); ++k) {
    EXPECT_LT(number(dt_rows[k], "duration_error"), number(dt_rows[k + 1], "duration_error"))
        << dt_rows[k].at("value") << " vs " << dt_rows[k + 1].at("value");
  }
  EXPECT_GE(number(dt_rows[0], "duration_error"), 0.0);
  EXPECT_LT(number(dt_rows[0], "duration_error"), 1e-3);
  // Energy drift of the elastic system: 0.02 t_R well below 0.4 t_R (measured 7e-6 vs 6e-3).
  EXPECT_GE(number(dt_rows[0], "energy_drift"), 0.0);
  EXPECT_LT(10.0 * number(dt_rows[0], "energy_drift"), number(dt_rows[4], "energy_drift"));

  // Every method finds the same contacts: the drum trajectories coincide with brute force.
  std::size_t methods = 0;
  for (const auto& row : rows) {
    if (row.at("knob") != "search") continue;
    ++methods;
    EXPECT_EQ(row.at("status"), "ok") << row.at("value");
    EXPECT_GE(number(row, "trajectory_rmin"), 0.0) << row.at("value");
    EXPECT_LT(number(row, "trajectory_rmin"), 1e-9) << row.at("value");
    EXPECT_GT(number(row, "wall_per_simulated_s"), 0.0) << row.at("value");
  }
  EXPECT_EQ(methods, 9u);

  // The Verlet skin changes which pairs are listed, never the forces: identical trajectories.
  // Re-ordering changes only the summation order (round-off), and every run stays stable.
  std::size_t skins = 0, sorts = 0;
  for (const auto& row : rows) {
    if (row.at("knob") == "verlet_skin") {
      ++skins;
      EXPECT_EQ(number(row, "trajectory_rmin"), 0.0) << row.at("value");
    } else if (row.at("knob") == "sort_every") {
      ++sorts;
      EXPECT_EQ(row.at("status"), "ok") << row.at("value");
    }
  }
  EXPECT_EQ(skins, 3u);
  EXPECT_EQ(sorts, 4u);
}

TEST(CliBenchAccuracy, BadOutputFolderIsExitTwo) {
  TempDir dir("bench-accuracy-bad");
  const auto file = dir.write("not_a_dir", "x");
  const auto r = run_cli("bench accuracy --quick --out " + (file / "sub").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace
}  // namespace drumlab::test
