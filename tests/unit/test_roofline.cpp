// `drumlab bench roofline` (app/bench/bench_roofline.*, roofline_model.*, machine_limits.*): the
// work model adds up the run's counts times the unit costs, a scene's law shape is read from the
// composed law, and the command end to end on a tiny drum writes a CSV whose step row is the sum
// of its phases, with roofs that order as a memory hierarchy must (L1 faster than memory). No
// speed is asserted.
//
// What ties the model to the engine (RooflineModel.CountsAreTheRunsAndTheModelPricesThem): the
// counts the model multiplies are the ones count_run reads from a run (the step's own StepWork),
// and each is checked step by step against an independent brute-force count over the particles
// at the positions the forces were computed at: the pairs within touching distance, the wall
// overlaps, the particles integrated, the re-orderings on their schedule; the model then prices
// exactly those units. This fails when the engine stops counting what the kernels evaluate (a
// pair or wall loop changed to evaluate other contacts, a counter dropped or moved), or when the
// model leaves a counted unit out. It cannot see a change inside a kernel that adds an operation
// per contact: the unit costs are hand counts written beside the lines they count
// (roofline_model.cpp), and no test can count a kernel's flops without hardware counters (none in
// the virtual machines this runs on: `perf stat` has no cycles there). The normal law is part of
// the law shape (a linear spring-dashpot without friction takes one square root fewer).
#include <gtest/gtest.h>

#include <sstream>

#include "app/bench/bench_roofline.hpp"
#include "app/bench/machine_limits.hpp"
#include "app/bench/roofline_model.hpp"
#include "engine/drum.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/search/contact_search.hpp"
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
  c.work.wall_contacts = 200;  // 20 a step
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

TEST(RooflineModel, LawShapeKnowsTheNormalLaw) {
  SmallDrumText t;
  t.friction = "0.0";
  const std::string contact = "[contact]\nnormal = \"linear\"\nlinear_stiffness = 1e4\n";
  const SceneConfig hertz = parse_scene(t.text(), "hertz.toml");
  const SceneConfig linear = parse_scene(t.text() + contact, "linear.toml");
  Particles p;
  p.add({0.0, 0.0, 0.0}, 0.01, 2500.0);
  const bench::LawShape h = bench::law_shape(hertz, p), l = bench::law_shape(linear, p);
  EXPECT_TRUE(h.hertz);
  EXPECT_FALSE(l.hertz);
  EXPECT_FALSE(l.tangential);
  // HertzNormal::force takes two square roots, LinearSpringDashpot::force one (its damping's).
  EXPECT_EQ(bench::touching_pair_cost(h).divsqrt - bench::touching_pair_cost(l).divsqrt, 1.0);
}

// Pairs within touching distance (what add_pair_forces counts) and wall overlaps (what the wall
// kernel evaluates), by brute force over all pairs and every wall part.
struct BruteCounts {
  std::uint64_t touching = 0;
  std::uint64_t wall_contacts = 0;
  std::uint64_t wall_particles = 0;  ///< particles with a wall overlap
};

BruteCounts brute_counts(const Particles& p, const Drum& drum) {
  BruteCounts b;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double cut = p.radius[i] + p.radius[j] + kTouchTolerance;
      b.touching += (p.position[i] - p.position[j]).squaredNorm() <= cut * cut ? 1 : 0;
    }
    std::uint64_t parts = 0;
    for (std::size_t part = 0; part < (drum.periodic() ? 1 : kWallParts); ++part) {
      parts += drum.contact(static_cast<WallPart>(part), p.position[i], p.radius[i]).overlap > 0.0;
    }
    b.wall_contacts += parts;
    b.wall_particles += parts > 0 ? 1 : 0;
  }
  return b;
}

TEST(RooflineModel, CountsAreTheRunsAndTheModelPricesThem) {
  SmallDrumText t;
  t.rolling_friction = "0.05";
  const SceneConfig scene =
      parse_scene(t.text() + "[performance]\nsort_every = 10\n", "roofline-counts.toml");
  Simulation sim(scene, random_fill(scene));
  sim.advance(200);  // a settled bed on the mantle and the caps
  const Drum drum(scene.drum);
  const std::uint64_t n = sim.particles().size();
  bench::RunCounts sum;
  BruteCounts brute;
  std::uint64_t listed = 0;
  constexpr std::uint64_t kSteps = 40;
  for (std::uint64_t k = 0; k < kSteps; ++k) {
    const std::uint64_t step = sim.steps();
    const bench::RunCounts c = bench::count_run(sim, 1);
    const BruteCounts b = brute_counts(sim.particles(), drum);
    SCOPED_TRACE(step);
    EXPECT_EQ(c.steps, 1u);
    EXPECT_EQ(c.work.particles, n);
    EXPECT_EQ(c.work.touching_pairs, b.touching);
    EXPECT_EQ(c.work.listed_pairs, sim.contacts().size());
    EXPECT_GE(c.work.listed_pairs, b.touching);
    EXPECT_EQ(c.work.wall_contacts, b.wall_contacts);
    EXPECT_GE(c.work.wall_candidates, b.wall_particles);
    EXPECT_EQ(c.work.reorders, step % 10 == 0 ? 1u : 0u);
    EXPECT_EQ(c.builds, 1u);  // m5: a grid built every step
    sum.steps += c.steps;
    sum.work.particles += c.work.particles;
    sum.work.listed_pairs += c.work.listed_pairs;
    sum.work.touching_pairs += c.work.touching_pairs;
    sum.work.wall_candidates += c.work.wall_candidates;
    sum.work.wall_contacts += c.work.wall_contacts;
    sum.work.reorders += c.work.reorders;
    sum.pairs_tested += c.pairs_tested;
    sum.builds += c.builds;
    brute.touching += b.touching;
    brute.wall_contacts += b.wall_contacts;
    listed += sim.contacts().size();
  }
  ASSERT_GT(brute.touching, 10 * kSteps);
  ASSERT_GT(brute.wall_contacts, 10 * kSteps);
  EXPECT_EQ(sum.work.reorders, kSteps / 10);
  // The model prices those units, and no others: forces are the listed pairs, the contacts
  // found by brute force and every particle's own force and torque; walls the candidates and
  // the overlaps found by brute force; integration every particle of every step.
  const bench::LawShape s = bench::law_shape(scene, sim.particles());
  ASSERT_TRUE(s.rolling);
  const bench::PhaseWork w = bench::phase_work(s, sum);
  const auto steps = static_cast<double>(kSteps), particles = static_cast<double>(n) * steps;
  const bench::Work forces = bench::listed_pair_cost() * static_cast<double>(listed) +
                             bench::touching_pair_cost(s) * static_cast<double>(brute.touching);
  EXPECT_DOUBLE_EQ(w.forces.flops, forces.flops);
  EXPECT_DOUBLE_EQ(w.forces.divsqrt, forces.divsqrt);
  EXPECT_DOUBLE_EQ(w.forces.stream, forces.stream + 48.0 * particles);
  const bench::Work walls =
      bench::wall_candidate_cost() * static_cast<double>(sum.work.wall_candidates) +
      bench::wall_contact_cost(s) * static_cast<double>(brute.wall_contacts);
  EXPECT_DOUBLE_EQ(w.walls.flops, walls.flops);
  EXPECT_DOUBLE_EQ(w.walls.divsqrt, walls.divsqrt);
  EXPECT_DOUBLE_EQ(w.integration.flops, bench::integrated_particle_cost(s).flops * particles);
  EXPECT_DOUBLE_EQ(w.reorder.flops,
                   bench::reordered_particle_cost(s).flops * static_cast<double>(n) * 4.0);
}

// A Verlet list patch is search work: its pass over every particle and its rewrite of the list,
// priced once per patch, and nothing when no patch ran.
TEST(RooflineModel, PricesTheVerletListPatches) {
  bench::LawShape s;
  s.particle_bytes = 200;
  bench::RunCounts c;
  c.verlet = true;
  c.steps = 10;
  c.work.particles = 10 * 1000;
  c.work.listed_pairs = 10 * 5000;
  c.pairs_tested = c.work.listed_pairs;  // the listed pairs' own tests only (force loop)
  const bench::PhaseWork unpatched = bench::phase_work(s, c);
  EXPECT_EQ(unpatched.search.flops, 0.0);
  c.patches = 3;
  const bench::PhaseWork patched = bench::phase_work(s, c);
  const bench::Work scan = bench::patched_particle_cost() * (3.0 * 1000.0);
  EXPECT_DOUBLE_EQ(patched.search.flops, scan.flops);
  EXPECT_DOUBLE_EQ(patched.search.divsqrt, scan.divsqrt);
  EXPECT_DOUBLE_EQ(patched.search.gather, scan.gather);
  EXPECT_GT(patched.search.stream, scan.stream + 3.0 * 5000.0 * 24.0);  // the list and histories
  EXPECT_DOUBLE_EQ(patched.forces.flops, unpatched.forces.flops);
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
