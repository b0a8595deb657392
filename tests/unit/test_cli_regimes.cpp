// `bench regimes --quick` (app/bench, in-process) end to end on the small regime drum with two
// Froude numbers and a short settling: exit 0, one CSV row per Froude number with the regime
// predicted from Fr, an observed regime that is one of the classifier's names and a finite angle of
// repose; bad Froude numbers give exit code 2 (the command itself). The regimes observed in so
// short a window are not asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/bench/bench_regimes.hpp"
#include "tests/unit/bench_runner.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

TEST(CliBench, RegimesQuickPrintsPredictedBesideObserved) {
  TempDir dir("bench-regimes");
  const auto out = dir.path() / "out";
  auto opt = bench_options<bench::RegimesBenchOptions>(
      std::string(DRUMLAB_SCENES_DIR) + "/regime_drum_small.toml", dir.path());
  opt.quick = true;
  opt.froude = {0.005, 1.0};
  opt.plan.settle_time = 0.2;
  const auto r = run_bench([&] { bench::run_bench_regimes(opt); });
  ASSERT_TRUE(r.ok) << r.output;
  EXPECT_NE(r.output.find("window"), std::string::npos) << r.output;
  const std::vector<std::string> lines = read_lines(out / "regimes_regime_drum_small.csv");
  ASSERT_EQ(lines.size(), 3u) << r.output;
  EXPECT_EQ(lines[0].rfind("scene,froude,omega,transient_s,window_s,steps,predicted,observed,", 0),
            0u);
  const std::set<std::string> names = {"unknown",   "slumping",    "rolling",
                                       "cascading", "cataracting", "centrifuging"};
  const std::vector<std::string> predicted = {"rolling/cascading", "centrifuging"};
  for (std::size_t k = 0; k < 2; ++k) {
    const auto f = split(lines[k + 1]);
    ASSERT_GE(f.size(), 10u) << lines[k + 1];
    EXPECT_EQ(f[6], predicted[k]);
    EXPECT_EQ(names.count(f[7]), 1u) << f[7];
    // omega = sqrt(Fr g / R), R = 0.15 m
    EXPECT_NEAR(std::atof(f[2].c_str()), std::sqrt(std::atof(f[1].c_str()) * 9.81 / 0.15), 1e-4);
    EXPECT_TRUE(std::isfinite(std::atof(f[9].c_str()))) << lines[k + 1];
  }
  const auto bad = run_cli("bench regimes --froude 0,1 --out " + out.string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
}

}  // namespace
}  // namespace drumlab::test
