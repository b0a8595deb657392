// The benches take every method and every fill a scene may name, as `drumlab run` does: a scene
// whose search is "auto" (resolved and reported as `run` reports it) and a scene filled from a
// CSV packing ([fill] kind = "file"). In-process through app/bench, a few steps each.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "app/bench/bench_state.hpp"
#include "app/bench/bench_throughput.hpp"
#include "app/bench/stress_scene.hpp"
#include "tests/unit/bench_runner.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

bench::ThroughputOptions tiny_throughput(const TempDir& dir, const std::filesystem::path& scene) {
  auto opt = bench_options<bench::ThroughputOptions>(scene.string(), dir.path());
  opt.methods = {"m5"};
  opt.steps = 3;
  opt.warmup = 1;
  opt.plan.settle_time = 0.002;
  opt.plan.turn_revolutions = 0.001;
  return opt;
}

TEST(BenchSession, ThroughputTakesAnAutoSceneAndReportsTheChoice) {
  TempDir dir("bench-auto");
  std::string text = small_drum_scene("dt_factor = 0.2\nduration = 0.01", "name = \"tiny_auto\"\n");
  text.replace(text.find("search = \"m5\""), 13, "search = \"auto\"");
  const auto scene = dir.write("auto.toml", text);
  const auto run = run_bench([&] { bench::run_bench_throughput(tiny_throughput(dir, scene)); });
  ASSERT_TRUE(run.ok) << run.output;
  const std::string& out = run.output;
  EXPECT_NE(out.find("search auto       -> "), std::string::npos) << out;
  const auto lines = read_lines(dir.path() / "out" / "throughput_tiny_auto.csv");
  ASSERT_EQ(lines.size(), 2u) << out;
  EXPECT_EQ(lines[1].rfind("tiny_auto,m5,", 0), 0u) << lines[1];

  // The cached state is reused, and "auto" is resolved on it again.
  testing::internal::CaptureStdout();
  const bench::RollingState cached =
      bench::rolling_state(scene.string(), tiny_throughput(dir, scene).plan);
  const std::string again = testing::internal::GetCapturedStdout();
  EXPECT_EQ(cached.origin.rfind("cached ", 0), 0u) << cached.origin;  // not "made ..., cached as"
  EXPECT_NE(again.find("search auto       -> "), std::string::npos) << again;
  EXPECT_NE(cached.scene.search_method, "auto");
}

TEST(BenchSession, ThroughputTakesAFileFillScene) {
  TempDir dir("bench-file-fill");
  bench::StressScene s;
  s.fill_file = "packing.csv";
  s.settle_time = 0.002;
  const std::string csv = bench::lattice_csv(s, 0.004, 0.02, 60);
  bench::write_text(dir.path() / s.fill_file, csv);
  const auto scene =
      bench::write_text(dir.path() / "file_fill.toml", "name = \"tiny_file\"\n" + s.toml());
  const std::size_t count = read_lines(dir.path() / s.fill_file).size() - 1;
  ASSERT_GT(count, 10u);
  const auto run = run_bench([&] { bench::run_bench_throughput(tiny_throughput(dir, scene)); });
  ASSERT_TRUE(run.ok) << run.output;
  const std::string& out = run.output;
  const auto lines = read_lines(dir.path() / "out" / "throughput_tiny_file.csv");
  ASSERT_EQ(lines.size(), 2u) << out;
  EXPECT_EQ(lines[1].rfind("tiny_file,m5,", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find("," + std::to_string(count) + ",3,"), std::string::npos) << lines[1];

  // The cached state is reused (a file fill names no count), and made again once the packing
  // changes (its last particle left out), the scene's text unchanged.
  const auto plan = tiny_throughput(dir, scene).plan;
  testing::internal::CaptureStdout();
  const bench::RollingState cached = bench::rolling_state(scene.string(), plan);
  bench::write_text(dir.path() / s.fill_file, csv.substr(0, csv.rfind('\n', csv.size() - 2) + 1));
  const bench::RollingState remade = bench::rolling_state(scene.string(), plan);
  testing::internal::GetCapturedStdout();
  EXPECT_EQ(cached.origin.rfind("cached ", 0), 0u) << cached.origin;  // not "made ..., cached as"
  EXPECT_EQ(cached.state.particles.size(), count);
  EXPECT_EQ(remade.origin.rfind("made in ", 0), 0u) << remade.origin;
  EXPECT_EQ(remade.state.particles.size(), count - 1);
}

}  // namespace
}  // namespace drumlab::test
