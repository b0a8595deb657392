// `run --observables FILE.csv`: a row per frame with the drum observables and the liquid's
// accounting; the films, bridges and wall bridges of every row add up to the first row's liquid
// (the scene's, conserved by every step) to 1e-12 relative; the angle columns are those of
// measure_drum's (within their ranges), the regime rules' wall speed omega R and field g; an
// unwritable path is one line, exit 2, before the run.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/run/observable_rows.hpp"
#include "tests/mpi/wet_drum_text.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

std::vector<std::vector<double>> rows_of(const std::filesystem::path& file, std::string& header) {
  std::ifstream in(file);
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::stringstream cells(line);
    std::vector<double> row;
    for (std::string c; std::getline(cells, c, ',');) row.push_back(std::stod(c));
    rows.push_back(row);
  }
  return rows;
}

TEST(ObservableRows, WetRunConservesItsLiquidInEveryRow) {
  TempDir dir("observables");
  // Liquid migration (films from the liquid content, bridges drawn from them, wall bridges).
  const std::string scene = dir.write("wet.toml", scene_text(wet_law())).string();
  const auto file = dir.path() / "obs.csv";
  const auto r = run_cli("run " + scene + " --steps 120 --every 20 --observables " + file.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("observables       7 frames in"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(file.string() + ".part"));
  std::string header;
  const auto rows = rows_of(file, header);
  EXPECT_EQ(header, cli::observable_columns());
  ASSERT_EQ(rows.size(), 7u);
  const double total = rows[0][9] + rows[0][10] + rows[0][11];
  ASSERT_GT(total, 0.0);
  double bridges = 0.0;
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 22u);
    EXPECT_EQ(row[13] + row[14] + row[15] + row[16], 0.0);  // no [[spray]]
    EXPECT_NEAR(row[9] + row[10] + row[11], total, 1e-12 * total);
    EXPECT_GE(row[3], -90.0);
    EXPECT_LE(row[3], 90.0);
    bridges = std::max(bridges, row[12]);
    // What the regime rules read: shares, the wall's speed omega R against gravity's field.
    EXPECT_GE(row[17], 0.0);
    EXPECT_LE(row[17], 1.0);
    EXPECT_GE(row[18], 0.0);
    EXPECT_LE(row[18], 1.0);
    EXPECT_NEAR(row[19], row[21] * 6.0, 1e-5 * row[19]);  // the scene's omega = 6 rad/s
    EXPECT_NEAR(row[20], 150.0, 1e-4);                    // and gravity 150 m/s^2 across
    EXPECT_GT(row[21], 0.0);
  }
  EXPECT_GT(bridges, 0.0);                     // a wet drum: the accounting is not of films alone
  EXPECT_GT(rows.back()[1], rows.front()[1]);  // the drum turned
}

TEST(ObservableRows, UnwritablePathIsOneLineBeforeTheRun) {
  TempDir dir("observables-bad");
  const std::string scene = dir.write("dry.toml", output_scene_text()).string();
  const auto r = run_cli("run " + scene + " --steps 10 --observables " +
                         (dir.path() / "no" / "such" / "o.csv").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--observables"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("steps "), std::string::npos) << r.output;  // it did not run
}

}  // namespace
}  // namespace drumlab::test
