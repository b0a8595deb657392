// `drumlab bench roofline` (app/bench/bench_roofline.*, roofline_model.*, machine_limits.*): the
// work model adds up the run's counts times the unit costs, a scene's law shape is read from the
// composed law, and the command end to end on a tiny drum writes a CSV whose step row is the sum
// of its phases, with roofs that order as a memory hierarchy must (L1 faster than memory). No
// speed is asserted.
#include <gtest/gtest.h>

#include <sstream>

#include "app/bench/bench_roofline.hpp"
#include "app/bench/machine_limits.hpp"
#include "app/bench/roofline_model.hpp"
#include "engine/scene/scene_config.hpp"
#include "tests/small_drum_text.hpp"
#include "tests/unit/bench_runner.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

std::string tiny_scene(const std::string& rolling_friction = "") {
  SmallDrumText t;
  t.header = "name = \"tiny_roofline\"\n";
  t.rolling_friction = rolling_friction;
  t.output = "diagnostics_every = 20";
  return t.text();
}

TEST(RooflineModel, PhaseWorkIsTheCountsTimesTheUnitCosts) {
  bench::LawShape s;
  s.particle_bytes = 161;
  bench::RunCounts c;
  c.steps = 10;
  c.work = {1000, 5000, 2000, 300, 1};  // 100 particles a step; 500 listed, 200 touching
  c.verlet = true;
  c.pairs_tested = 5000 + 700;  // the list every step and one rebuild's 700 tests
  c.builds = 1;
  c.wall_contacts_per_step = 20.0;
  const bench::PhaseWork w = bench::phase_work(s, c);
  const bench::Work pair = bench::touching_pair_cost(s);
  EXPECT_DOUBLE_EQ(w.forces.flops, 5000 * bench::listed_pair_cost().flops + 2000 * pair.flops);
  EXPECT_DOUBLE_EQ(w.forces.divsqrt, 2000 * pair.divsqrt);
  EXPECT_DOUBLE_EQ(w.search.flops, 100 * bench::binned_particle_cost().flops +
                                       700 * bench::tested_pair_cost().flops);
  EXPECT_DOUBLE_EQ(w.walls.flops, 300 * bench::wall_candidate_cost().flops +
                                      200 * bench::wall_contact_cost(s).flops);
  EXPECT_DOUBLE_EQ(w.integration.stream, 1000 * 416.0);
  // Each part of the law costs what its kernel computes: tangential history and rolling add.
  bench::LawShape normal_only = s;
  normal_only.tangential = false;
  bench::LawShape rolling = s;
  rolling.rolling = true;
  EXPECT_LT(bench::touching_pair_cost(normal_only).flops, pair.flops);
  EXPECT_GT(bench::touching_pair_cost(rolling).divsqrt, pair.divsqrt);
}

TEST(RooflineModel, LawShapeIsTheComposedLaws) {
  const SceneConfig dry = parse_scene(tiny_scene(), "tiny.toml");
  Particles p;
  p.add({0.0, 0.0, 0.0}, 0.01, 2500.0);
  const bench::LawShape s = bench::law_shape(dry, p);
  EXPECT_TRUE(s.tangential);
  EXPECT_FALSE(s.rolling);
  EXPECT_FALSE(s.cohesive);
  // position, velocity, omega, force, torque; radius, mass, 1/m, 1/I; size class; id.
  EXPECT_EQ(s.particle_bytes, 5 * sizeof(Vec3) + 4 * sizeof(double) + 1 + sizeof(Index));
  const SceneConfig rolling = parse_scene(tiny_scene("0.1"), "tiny.toml");
  EXPECT_TRUE(bench::law_shape(rolling, p).rolling);
}

TEST(MachineLimits, RoofsArePositiveAndL1IsFasterThanMemory) {
  const bench::MachineLimits m = bench::measure_machine_limits(true);
  EXPECT_GT(m.peak_gflops, 0.0);
  EXPECT_GT(m.divsqrt_per_s, 0.0);
  ASSERT_EQ(m.levels.size(), 4u);
  EXPECT_EQ(m.levels.back().name, "memory");
  EXPECT_GT(m.levels.front().gbs, m.levels.back().gbs);
  EXPECT_EQ(m.level_for(1.0).name, "L1");
  EXPECT_EQ(m.level_for(1e12).name, "memory");
}

TEST(CliRoofline, WritesEveryPhaseAndTheStepIsTheirSum) {
  TempDir dir("bench-roofline");
  const auto scene = dir.write("tiny.toml", tiny_scene());
  auto opt = bench_options<bench::RooflineOptions>(scene.string(), dir.path());
  opt.steps = 20;
  opt.warmup = 2;
  opt.quick = true;
  const auto r = run_bench([&] { bench::run_bench_roofline(opt); });
  ASSERT_TRUE(r.ok) << r.output;
  const auto lines = read_lines(dir.path() / "out" / "roofline_tiny_roofline.csv");
  ASSERT_EQ(lines.size(), 7u) << r.output;
  const char* phases[] = {"search", "pair forces", "walls", "integration", "re-ordering", "step"};
  double seconds = 0.0, flops = 0.0, step_seconds = 0.0, step_flops = 0.0;
  for (int k = 0; k < 6; ++k) {
    std::vector<std::string> cells;
    std::stringstream row(lines[k + 1]);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_GE(cells.size(), 8u) << lines[k + 1];
    EXPECT_EQ(cells[3], phases[k]);
    EXPECT_NE(r.output.find(phases[k]), std::string::npos);
    const double s = std::stod(cells[4]), f = std::stod(cells[6]);
    EXPECT_GE(s, 0.0);
    if (k < 5) {
      seconds += s;
      flops += f;
    } else {
      step_seconds = s;
      step_flops = f;
    }
  }
  EXPECT_NEAR(step_seconds, seconds, 1e-5 * step_seconds);
  EXPECT_NEAR(step_flops, flops, 1e-5 * step_flops);
  EXPECT_GT(step_flops, 0.0);
}

TEST(CliRoofline, UnknownMethodGivesExitCode2AndNoFile) {
  TempDir dir("bench-roofline-bad");
  const auto scene = dir.write("tiny.toml", tiny_scene());
  const auto r = run_cli("bench roofline --quick --steps 2 --method m9 --scene " + scene.string() +
                         " --cache " + (dir.path() / "cache").string() + " --out " +
                         (dir.path() / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("drumlab: error: "), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "roofline_tiny_roofline.csv"));
}

}  // namespace
}  // namespace drumlab::test
