// `drumlab info` prints the needs / skips section; `bench skips` (app/bench, in-process) runs end
// to end on a tiny drum: one CSV row per skip, and where the two paths have the same physics their
// positions agree to round-off (friction 0 vs a tiny friction, rolling 0 vs tiny, m2 vs m3/m5,
// with/without writers). No speeds are asserted.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/bench/bench_skips.hpp"
#include "tests/unit/bench_runner.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  bool quoted = false;
  for (const char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.push_back(cell);
      cell.clear();
    } else {
      cell += c;
    }
  }
  out.push_back(cell);
  return out;
}

TEST(CliInfo, PrintsNeedsAndSkipsWithReasons) {
  TempDir dir("info-skips");
  std::string text = small_drum_scene();
  text.replace(text.find("friction = 0.5"), 14, "friction = 0.0");
  text.replace(text.find("omega = 2.0"), 11, "omega = 2.0\nends = \"periodic\"");
  const auto scene = dir.write("frictionless.toml", text);
  const auto r = run_cli("info " + scene.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* expected : {
           "needs / skips",
           "skipped         tangential history (particle-particle)",
           "material.friction = 0: no tangential force, no history update",
           "skipped         tangential history (particle-wall)",
           "skipped         rotation (angular velocity)",
           "skipped         rolling resistance (particle-particle)",
           "skipped         cohesion",
           "skipped         end-cap contacts",
           "skipped         triangle walls",
           "available       3D search grid",
           "command line    output writers / VTK objects",
       }) {
    EXPECT_NE(r.output.find(expected), std::string::npos) << expected << "\n" << r.output;
  }
  const auto demo = run_cli("info " + std::string(DRUMLAB_SCENES_DIR) + "/drum_demo.toml");
  ASSERT_EQ(demo.exit_code, 0) << demo.output;
  EXPECT_NE(demo.output.find("needed          tangential history (particle-particle)"),
            std::string::npos)
      << demo.output;
  EXPECT_NE(demo.output.find("needed          end-cap contacts"), std::string::npos);
  const auto lifters = run_cli("info " + std::string(DRUMLAB_SCENES_DIR) + "/lifter_drum.toml");
  ASSERT_EQ(lifters.exit_code, 0) << lifters.output;
  EXPECT_NE(lifters.output.find("needed          triangle walls"), std::string::npos)
      << lifters.output;
}

TEST(CliBench, SkipsWritesOneRowPerSkipAndSamePhysicsAgrees) {
  TempDir dir("bench-skips");
  const auto scene = dir.write(
      "tiny.toml", small_drum_scene("dt_factor = 0.2\nduration = 0.01", "name = \"tiny_skips\"\n"));
  const auto out = dir.path() / "out";
  auto opt = bench_options<bench::SkipsBenchOptions>(scene.string(), dir.path());
  opt.steps = 20;
  opt.repeats = 1;
  opt.every = 10;
  opt.plan.turn_revolutions = 0.02;
  const auto r = run_bench([&] { bench::run_bench_skips(opt); });
  ASSERT_TRUE(r.ok) << r.output;
  const auto lines = read_lines(out / "skips_tiny_skips.csv");
  ASSERT_EQ(lines.size(), 8u) << r.output;
  EXPECT_EQ(lines[0],
            "scene,skip,general_path,measure,steps,repeats,with_skip_cpu_s_per_step,"
            "without_skip_cpu_s_per_step,gain_cpu,with_skip_wall_s_per_step,"
            "without_skip_wall_s_per_step,gain_wall,same_physics,max_dx_over_rmin,note");
  const std::vector<std::string> skips = {"friction 0",       "rolling 0",     "2D grid m2 vs m3",
                                          "2D grid m2 vs m5", "periodic ends", "cohesion off",
                                          "no writers"};
  for (std::size_t k = 0; k < skips.size(); ++k) {
    const auto f = fields(lines[k + 1]);
    ASSERT_EQ(f.size(), 15u) << lines[k + 1];
    EXPECT_EQ(f[1], skips[k]);
    EXPECT_GT(std::atof(f[6].c_str()), 0.0) << lines[k + 1];
    EXPECT_GT(std::atof(f[7].c_str()), 0.0) << lines[k + 1];
    EXPECT_GT(std::atof(f[9].c_str()), 0.0) << lines[k + 1];
    if (skips[k] == "periodic ends") {
      EXPECT_EQ(f[12], "0");
      EXPECT_TRUE(f[13].empty());
    } else {
      // Same physics: positions after 20 steps agree to round-off (relative to r_min).
      EXPECT_EQ(f[12], "1");
      ASSERT_FALSE(f[13].empty()) << lines[k + 1];
      EXPECT_LT(std::atof(f[13].c_str()), 1e-9) << lines[k + 1];
    }
  }
  EXPECT_FALSE(std::filesystem::exists(out / "skips_tiny_skips_writers"));  // scratch removed
}

}  // namespace
}  // namespace drumlab::test
