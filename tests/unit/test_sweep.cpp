// drumlab sweep: a 2 x 2 sweep (a key's values x seeds) writes the rows it should, each row's
// window mean and spread recomputed here from the run's own observables table; a sweep killed
// with SIGKILL keeps its finished rows and, run again, runs only the rest; bad --set specs, keys
// and values exit 2 with one line before anything runs.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "app/cli/sweep_results.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string c; std::getline(in, c, ',');) out.push_back(c);
  return out;
}

TEST(Sweep, WritesARowPerRunWithTheWindowStatistics) {
  TempDir dir("sweep");
  const std::string scene = dir.write("dry.toml", output_scene_text()).string();
  const auto out = dir.path() / "out";
  const auto r = run_cli("sweep " + scene + " --set material.friction=0.2,0.6 --seeds 1,2 --out " +
                         out.string() + " --jobs 2 --steps 60 --every 10 --window-from 0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto table = lines_of(out / "sweep.csv");
  ASSERT_EQ(table.size(), 5u) << r.output;
  const std::vector<std::string> header = cells(table[0]);
  EXPECT_EQ(header[1], "material.friction");
  EXPECT_EQ(header[2], "seed");
  const std::string want[4][2] = {{"0.2", "1"}, {"0.2", "2"}, {"0.6", "1"}, {"0.6", "2"}};
  for (int k = 0; k < 4; ++k) {
    const std::vector<std::string> row = cells(table[static_cast<std::size_t>(k + 1)]);
    ASSERT_EQ(row.size(), header.size());
    EXPECT_EQ(row[1], want[k][0]);
    EXPECT_EQ(row[2], want[k][1]);
    // The run's scene has the value set, and its mean / sd are those of its table (7 frames).
    const auto run_dir = out / "runs" / row[0];
    std::ifstream s(run_dir / "scene.toml");
    std::stringstream text;
    text << s.rdbuf();
    EXPECT_NE(text.str().find("friction = " + want[k][0]), std::string::npos) << text.str();
    const cli::CsvTable obs = cli::read_numeric_csv(run_dir / "observables.csv");
    ASSERT_EQ(obs.rows.size(), 7u);
    const std::size_t c = obs.column("angle_com_deg", run_dir / "observables.csv");
    double mean = 0.0, ss = 0.0;
    for (const auto& o : obs.rows) mean += o[c] / 7.0;
    for (const auto& o : obs.rows) ss += (o[c] - mean) * (o[c] - mean);
    const auto at = [&](const char* name) {
      return std::stod(row[static_cast<std::size_t>(std::find(header.begin(), header.end(), name) -
                                                    header.begin())]);
    };
    EXPECT_NEAR(at("angle_com_deg"), mean, 1e-5 * std::max(1.0, std::abs(mean)));
    EXPECT_NEAR(at("angle_com_deg_sd"), std::sqrt(ss / 6.0), 1e-5 * std::max(1.0, mean));
    EXPECT_EQ(at("frames"), 7.0);
  }
#if DRUMLAB_TESTS_RENDER
  EXPECT_GT(std::filesystem::file_size(out / "sweep.png"), 1000u);
#else  // a build without VTK draws no chart
  EXPECT_FALSE(std::filesystem::exists(out / "sweep.png"));
#endif
  // Run again: everything is done, nothing runs, the table is the same.
  const auto again =
      run_cli("sweep " + scene + " --set material.friction=0.2,0.6 --seeds 1,2 --out " +
              out.string() + " --steps 60 --every 10 --window-from 0");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("4 runs (4 finished before)"), std::string::npos) << again.output;
  EXPECT_EQ(lines_of(out / "sweep.csv"), table);
}

TEST(Sweep, KilledSweepKeepsItsRowsAndResumes) {
  TempDir dir("sweep-kill");
  const std::string scene = dir.write("dry.toml", output_scene_text()).string();
  const auto out = dir.path() / "out";
  const std::string spec = "material.friction=0.2,0.4,0.6,0.8";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::freopen("/dev/null", "w", stdout);
    ::execl(DRUMLAB_CLI, DRUMLAB_CLI, "sweep", scene.c_str(), "--set", spec.c_str(), "--out",
            out.c_str(), "--steps", "300", "--every", "50", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto start = std::chrono::steady_clock::now();
  while (lines_of(out / "sweep.csv").size() < 2 &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(120)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  const auto kept = lines_of(out / "sweep.csv");
  ASSERT_GE(kept.size(), 2u);
  ASSERT_LT(kept.size(), 5u) << "the sweep finished before it was killed";
  const auto r = run_cli("sweep " + scene + " --set " + spec + " --out " + out.string() +
                         " --steps 300 --every 50");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(fmt::format("4 runs ({} finished before)", kept.size() - 1)),
            std::string::npos)
      << r.output;
  const auto table = lines_of(out / "sweep.csv");
  ASSERT_EQ(table.size(), 5u);
  for (std::size_t k = 0; k < kept.size(); ++k) EXPECT_EQ(table[k], kept[k]);
}

TEST(Sweep, BadSetsAreOneLineBeforeAnythingRuns) {
  TempDir dir("sweep-bad");
  const std::string scene = dir.write("dry.toml", output_scene_text()).string();
  const auto out = dir.path() / "out";
  for (const auto& [set, says] : {std::pair<std::string, std::string>{"friction", "not KEY=V1,V2"},
                                  {"material.friction=0.2,,0.3", "an empty value"},
                                  {"material.fricton=0.2", "fricton"},
                                  {"material.friction=-1", "friction"},
                                  {"fill.count=lots", "not a whole number"},
                                  {"drum=3", "array or table"}}) {
    const auto r = run_cli("sweep " + scene + " --set " + set + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << set << ": " << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << set << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << set;
  }
}

}  // namespace
}  // namespace drumlab::test
