// `bench throughput` and `bench search` (app/bench, in-process) end to end on a tiny drum with few
// steps: no error, the CSV has the expected header and one row per method, the chart is a valid PNG
// (when the CLI is built with rendering), the rolling state is cached and reused; bad output
// folders, unknown methods and bad scenes give exit code 2 and leave no file (the command itself).
// No speeds are asserted.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "app/bench/bench_search.hpp"
#include "app/bench/bench_throughput.hpp"
#include "tests/unit/bench_runner.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

std::string tiny_scene() {
  return small_drum_scene("dt_factor = 0.2\nduration = 0.01", "name = \"tiny_bench\"\n");
}

/// PNG signature and an IHDR chunk with a non-zero size.
bool is_png(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(24, '\0');
  if (!in.read(head.data(), 24)) return false;
  const std::string signature = "\x89PNG\r\n\x1a\n";
  auto be32 = [&](int at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(head[at])) << 24) |
           (static_cast<unsigned>(static_cast<unsigned char>(head[at + 1])) << 16) |
           (static_cast<unsigned>(static_cast<unsigned char>(head[at + 2])) << 8) |
           static_cast<unsigned>(static_cast<unsigned char>(head[at + 3]));
  };
  return head.substr(0, 8) == signature && head.substr(12, 4) == "IHDR" && be32(16) > 0 &&
         be32(20) > 0;
}

bool built_without_render(const std::string& output) {
  return output.find("built without rendering") != std::string::npos;
}

TEST(CliBench, ThroughputWritesOneRowPerMethodAndAChart) {
  TempDir dir("bench-throughput");
  const auto scene = dir.write("tiny.toml", tiny_scene());
  const auto out = dir.path() / "out";
  const std::string common = "bench throughput --scene " + scene.string() + " --cache " +
                             (dir.path() / "cache").string() + " --out " + out.string() +
                             " --steps 5 --warmup 1";
  // As `drumlab ` + common: the scene, cache and output folders, 5 timed steps after 1 warm-up.
  const auto options = [&](std::vector<std::string> methods) {
    auto opt = bench_options<bench::ThroughputOptions>(scene.string(), dir.path());
    opt.steps = 5;
    opt.warmup = 1;
    opt.methods = std::move(methods);
    return opt;
  };
  const auto r = run_bench([&] {
    bench::run_bench_throughput(options({"m5", "verlet", "mlgrid", "brute"}));
  });
  ASSERT_TRUE(r.ok) << r.output;
  EXPECT_NE(r.output.find("cached as"), std::string::npos) << r.output;
  const auto lines = read_lines(out / "throughput_tiny_bench.csv");
  ASSERT_EQ(lines.size(), 5u) << r.output;
  EXPECT_EQ(lines[0],
            "scene,method,sort_every,threads,particles,steps,stepping_s,particle_steps_per_s,"
            "particle_steps_per_cpu_s,speedup,"
            "search_share,forces_share,walls_share,integration_share,cells_per_particle,"
            "tested_per_particle,contacts_per_particle,tested_per_contact,verlet_rebuilds,"
            "verlet_patches,heap_bytes_per_particle");
  const std::vector<std::string> methods = {"m5", "verlet", "mlgrid", "brute"};
  for (std::size_t k = 0; k < methods.size(); ++k) {
    EXPECT_EQ(lines[k + 1].rfind("tiny_bench," + methods[k] + ",100,1,300,5,", 0), 0u)
        << lines[k + 1];
  }
  for (std::size_t k = 1; k < lines.size(); ++k) {
    // Process CPU time per row: a positive rate (a CPU-bound step loop on one thread cannot use
    // much more CPU than wall time, so it stays near the wall-clock rate or above it).
    std::vector<std::string> cells;
    std::stringstream row(lines[k]);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_GT(cells.size(), 8u);
    const double wall_rate = std::stod(cells[7]);
    const double cpu_rate = std::stod(cells[8]);
    EXPECT_GT(cpu_rate, 0.0) << lines[k];
    EXPECT_GT(cpu_rate, 0.5 * wall_rate) << lines[k];
  }
  if (!built_without_render(r.output)) {
    EXPECT_TRUE(is_png(out / "throughput_tiny_bench.png"));
  }

  // The second run reuses the cached rolling state; two thread counts give two rows per method.
  bench::ThroughputOptions two_threads = options({"m2"});
  two_threads.threads = 2;
  const auto again = run_bench([&] { bench::run_bench_throughput(two_threads); });
  ASSERT_TRUE(again.ok) << again.output;
  EXPECT_NE(again.output.find("cached "), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find("cached as"), std::string::npos) << again.output;
  EXPECT_EQ(read_lines(out / "throughput_tiny_bench.csv").size(), 3u);

  // A sort-interval sweep: one row per interval, labelled with it.
  bench::ThroughputOptions sorts = options({"verlet"});
  sorts.sort_every = {0, 2};
  sorts.repeats = 2;
  const auto sweep = run_bench([&] { bench::run_bench_throughput(sorts); });
  ASSERT_TRUE(sweep.ok) << sweep.output;
  EXPECT_NE(sweep.output.find("verlet sort 2"), std::string::npos) << sweep.output;
  const auto rows = read_lines(out / "throughput_tiny_bench.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].rfind("tiny_bench,verlet,0,1,300,5,", 0), 0u) << rows[1];
  EXPECT_EQ(rows[2].rfind("tiny_bench,verlet,2,1,300,5,", 0), 0u) << rows[2];
  EXPECT_NE(run_cli(common + " --sort-every -1").exit_code, 0);
}

TEST(CliBench, SearchWritesOneRowPerMethodAndAChart) {
  TempDir dir("bench-search");
  const auto scene = dir.write("tiny.toml", tiny_scene());
  const auto out = dir.path() / "out";
  // As `drumlab bench search --no-table1 --steps 3 --repeats 1`.
  auto opt = bench_options<bench::SearchBenchOptions>(scene.string(), dir.path());
  opt.table1 = false;
  opt.steps = 3;
  opt.repeats = 1;
  const auto r = run_bench([&] { bench::run_bench_search(opt); });
  ASSERT_TRUE(r.ok) << r.output;
  const auto lines = read_lines(out / "search_tiny_bench.csv");
  ASSERT_FALSE(lines.empty()) << r.output;
  EXPECT_EQ(lines[0],
            "dataset,method,particles,contacts_per_particle,cells_per_particle,tested_per_particle,"
            "tested_per_contact,first_call_s,call_s,build_s,visit_s,step_s,search_share,"
            "paper_operations_per_particle");
  const std::vector<std::string> methods = {
      "brute", "m1", "m2", "m3", "m4", "m5", "mlgrid", "verlet", "verlet:m2", "verlet:mlgrid"};
  ASSERT_EQ(lines.size(), methods.size() + 1) << r.output;
  for (std::size_t k = 0; k < methods.size(); ++k) {
    EXPECT_EQ(lines[k + 1].rfind("tiny_bench_flowing," + methods[k] + ",300,", 0), 0u)
        << lines[k + 1];
  }
  if (!built_without_render(r.output)) {
    EXPECT_TRUE(is_png(out / "search_tiny_bench.png"));
  }
}

TEST(CliBench, BadInputGivesExitCode2AndNoFile) {
  TempDir dir("bench-bad");
  const auto scene = dir.write("tiny.toml", tiny_scene());
  const auto blocker = dir.write("file", "not a folder");
  const std::string cache = " --cache " + (dir.path() / "cache").string();
  const std::vector<std::string> cases = {
      "bench throughput --steps 2 --scene " + scene.string() + cache + " --out " +
          (blocker / "out").string(),
      "bench search --no-table1 --scene " + scene.string() + cache + " --out " +
          (blocker / "out").string(),
      "bench throughput --methods m9 --scene " + scene.string() + cache + " --out " +
          (dir.path() / "out").string(),
      "bench throughput --scene " + (dir.path() / "missing.toml").string() + cache + " --out " +
          (dir.path() / "out").string(),
  };
  for (const std::string& args : cases) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("drumlab: error: "), std::string::npos) << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "throughput_tiny_bench.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "cache"));
  std::size_t files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path())) {
    files += e.is_regular_file() ? 1 : 0;
  }
  EXPECT_EQ(files, 2u);  // tiny.toml and the blocking file only
}

}  // namespace
}  // namespace drumlab::test
