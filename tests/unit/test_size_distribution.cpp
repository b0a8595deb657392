// Size distributions of a particle class (engine/scene/size_distribution.hpp): the drawn radii
// against the requested moments (closed forms of the truncated normal and lognormal, the exact
// mean of a table), inside [min, max], the same for a seed; the scene keys and their errors (one
// line naming file and key, exit 2); a random fill that draws them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "engine/fill/file_fill.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/io/restart_check.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/scene/size_distribution.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

constexpr std::size_t kDraws = 200000;
/// Statistical tolerance: 5 standard errors (a false alarm about once in 1.7 million runs; the
/// seeds are fixed, so a run either passes or fails for good).
constexpr double kStandardErrors = 5.0;

struct Sample {
  double mean = 0.0, sd = 0.0, m4 = 0.0, min = INFINITY, max = -INFINITY;
};

Sample draw_sample(const SizeDistribution& d, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> r(kDraws);
  Sample s;
  for (double& x : r) {
    x = d.draw(rng);
    s.mean += x;
    s.min = std::min(s.min, x);
    s.max = std::max(s.max, x);
  }
  s.mean /= kDraws;
  double var = 0.0;
  for (const double x : r) {
    var += (x - s.mean) * (x - s.mean);
    s.m4 += std::pow(x - s.mean, 4);
  }
  s.sd = std::sqrt(var / (kDraws - 1));
  s.m4 /= kDraws;
  return s;
}

/// The sample's mean and standard deviation within kStandardErrors of `mean` and `sd`: the mean's
/// standard error sd / sqrt(N), the standard deviation's sqrt(mu4 - sd^4) / (2 sd sqrt(N)).
void expect_moments(const Sample& s, double mean, double sd) {
  const double n = static_cast<double>(kDraws);
  EXPECT_NEAR(s.mean, mean, kStandardErrors * sd / std::sqrt(n));
  const double se_sd = std::sqrt(s.m4 - std::pow(s.sd, 4)) / (2.0 * s.sd * std::sqrt(n));
  EXPECT_NEAR(s.sd, sd, kStandardErrors * se_sd);
}

/// Truncated normal at +-t: the mean stays, variance sigma^2 (1 - 2 t phi(t) / (2 Phi(t) - 1)).
double truncated_normal_sd(double sigma, double t) {
  const double phi = std::exp(-0.5 * t * t) / std::sqrt(2.0 * std::numbers::pi);
  return sigma * std::sqrt(1.0 - 2.0 * t * phi / std::erf(t / std::numbers::sqrt2));
}

/// The documented algorithm, written out: uniforms from the top 53 bits, Box-Muller's cosine.
double first_normal_of_seed_42() {
  std::mt19937_64 rng(42);
  for (;;) {
    const double u1 = 1.0 - static_cast<double>(rng() >> 11) * 0x1.0p-53;
    const double u2 = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    if (std::abs(z) <= 3.0) return z;
  }
}

TEST(SizeDistribution, NormalDrawsHaveTheTruncatedMoments) {
  for (const double t : {3.0, 1.0}) {
    SCOPED_TRACE(t);
    const SizeDistribution d = SizeDistribution::normal(2e-3, 2e-4, t);
    EXPECT_DOUBLE_EQ(d.min_radius(), 2e-3 - t * 2e-4);
    EXPECT_DOUBLE_EQ(d.max_radius(), 2e-3 + t * 2e-4);
    EXPECT_DOUBLE_EQ(d.mean_radius(), 2e-3);
    EXPECT_NEAR(d.radius_sd(), truncated_normal_sd(2e-4, t), 1e-12 * 2e-4);
    const Sample s = draw_sample(d, 7);
    expect_moments(s, 2e-3, truncated_normal_sd(2e-4, t));
    EXPECT_GE(s.min, d.min_radius());
    EXPECT_LE(s.max, d.max_radius());
  }
  // t = 1 cuts the spread by almost half: the test sees the truncation, not just the normal.
  EXPECT_LT(truncated_normal_sd(1.0, 1.0), 0.6);
}

TEST(SizeDistribution, LognormalHasTheRequestedMeanAndSpreadBeforeTruncation) {
  const double mean = 1e-3, sigma = 5e-4;  // a wide spread: skewed, mean - 3 sigma < 0
  const double s2 = std::log1p(0.25);
  const double mu = std::log(mean) - 0.5 * s2;
  const SizeDistribution wide = SizeDistribution::lognormal(mean, sigma, 50.0);  // no cut
  EXPECT_NEAR(wide.mean_radius(), mean, 1e-12 * mean);
  EXPECT_NEAR(wide.radius_sd(), sigma, 1e-9 * sigma);
  expect_moments(draw_sample(wide, 11), mean, sigma);

  const SizeDistribution cut = SizeDistribution::lognormal(mean, sigma, 2.0);
  EXPECT_NEAR(cut.min_radius(), std::exp(mu - 2.0 * std::sqrt(s2)), 1e-15);
  EXPECT_NEAR(cut.max_radius(), std::exp(mu + 2.0 * std::sqrt(s2)), 1e-15);
  EXPECT_GT(cut.min_radius(), 0.0);
  EXPECT_LT(cut.radius_sd(), 0.9 * sigma);  // the cut is visible in the closed form
  const Sample s = draw_sample(cut, 12);
  expect_moments(s, cut.mean_radius(), cut.radius_sd());
  EXPECT_GE(s.min, cut.min_radius());
  EXPECT_LE(s.max, cut.max_radius());
}

TEST(SizeDistribution, TableDrawsTheSharesExactMean) {
  const SizeDistribution d = SizeDistribution::table({1e-3, 3e-3, 2e-3}, {1.0, 1.0, 2.0});
  const double mean = (1e-3 + 3e-3 + 2.0 * 2e-3) / 4.0;
  const double second = (1e-6 + 9e-6 + 2.0 * 4e-6) / 4.0;
  EXPECT_DOUBLE_EQ(d.mean_radius(), mean);
  EXPECT_NEAR(d.mean_cube(), (1e-9 + 27e-9 + 2.0 * 8e-9) / 4.0, 1e-24);
  EXPECT_EQ(d.min_radius(), 1e-3);
  EXPECT_EQ(d.max_radius(), 3e-3);
  const Sample s = draw_sample(d, 13);
  expect_moments(s, mean, std::sqrt(second - mean * mean));
  EXPECT_EQ(s.min, 1e-3);
  EXPECT_EQ(s.max, 3e-3);
  EXPECT_TRUE(d.holds(2e-3, 1e-9));
  EXPECT_FALSE(d.holds(2.5e-3, 1e-6));  // a table holds its radii, not the range between them
}

TEST(SizeDistribution, ASeedGivesTheSameRadiiAndOneRadiusDrawsNothing) {
  const SizeDistribution d = SizeDistribution::normal(2e-3, 2e-4, 3.0);
  std::mt19937_64 a(42), b(42), c(43);
  bool differs = false;
  for (int k = 0; k < 1000; ++k) {
    const double x = d.draw(a);
    EXPECT_EQ(x, d.draw(b));
    differs = differs || x != d.draw(c);
  }
  EXPECT_TRUE(differs);
  // The first radius of seed 42, pinned: Box-Muller on 53-bit uniforms of mt19937_64, no <random>
  // distribution, so another standard library gives the same value (up to libm's log/cos).
  std::mt19937_64 pinned(42);
  EXPECT_EQ(d.draw(pinned), 2e-3 + 2e-4 * first_normal_of_seed_42());
  std::mt19937_64 untouched(5), reference(5);
  EXPECT_EQ(SizeDistribution::single(1e-3).draw(untouched), 1e-3);
  EXPECT_EQ(untouched(), reference());
}

/// A small drum of one normal class (the lead's MercuryDPM drum in miniature).
std::string normal_drum(const std::string& size_keys, const std::string& search = "m5") {
  return "search = \"" + search +
         "\"\n[drum]\ndiameter = 0.08\ndepth = 0.02\nomega = 1.0\n"
         "[[particles]]\nname = \"grain\"\n" +
         size_keys +
         "\n[material]\ndensity = 1500.0\nyoungs_modulus = 5e6\npoisson_ratio = 0.3\n"
         "restitution = 0.5\nfriction = 0.5\n[fill]\ncount = 400\nsettle_time = 0.01\n"
         "[time]\ndt_factor = 0.2\nduration = 0.01\n";
}

const char* const kNormal =
    "distribution = \"normal\"\nradius = 2e-3\nradius_sigma = 2e-4\ntruncate = 3";

TEST(SizeDistributionScene, KeysLoadAndTheFillDrawsRadiiInsideTheClass) {
  const SceneConfig s = parse_scene(normal_drum(kNormal), "normal.toml");
  const ParticleClass& c = s.classes.at(0);
  EXPECT_EQ(c.distribution, SizeKind::normal);
  EXPECT_DOUBLE_EQ(s.min_radius(), 2e-3 - 6e-4);
  EXPECT_DOUBLE_EQ(s.max_radius(), 2e-3 + 6e-4);
  const Particles p = random_fill(s);
  ASSERT_EQ(p.size(), 400u);
  double mean = 0.0;
  for (const double r : p.radius) {
    EXPECT_GE(r, c.min_radius());
    EXPECT_LE(r, c.max_radius());
    mean += r / 400.0;
  }
  EXPECT_NEAR(mean, 2e-3, kStandardErrors * 2e-4 / std::sqrt(400.0));
  EXPECT_NE(p.min_radius(), p.max_radius());
  EXPECT_EQ(random_fill(s).radius, p.radius);  // the fill's seed fixes the radii

  const SceneConfig table = parse_scene(
      normal_drum("distribution = \"table\"\nradii = [1.5e-3, 2.5e-3]\nshares = [3, 1]"),
      "table.toml");
  EXPECT_DOUBLE_EQ(table.classes[0].mean_radius(), 1.75e-3);
  EXPECT_EQ(table.max_radius(), 2.5e-3);
}

TEST(SizeDistributionScene, ClassCountsUseTheMeanVolume) {
  // Two classes of equal solid volume: one of 2 mm, one a table of 1 and 3 mm in equal number.
  SceneConfig s = parse_scene(normal_drum("radius = 2e-3\nvolume_fraction = 0.5\n[[particles]]\n"
                                          "name = \"mix\"\ndistribution = \"table\"\n"
                                          "radii = [1e-3, 3e-3]\nshares = [1, 1]\n"
                                          "volume_fraction = 0.5"),
                              "two.toml");
  s.fill.count = 4400;
  // E[r^3] of the mix: (1 + 27) / 2 = 14 mm^3 against 8 mm^3: 8 / 14 as many particles.
  const auto counts = class_counts(s);
  EXPECT_EQ(counts[0], 2800u);
  EXPECT_EQ(counts[1], 1600u);
}

TEST(SizeDistributionScene, FileFillAndRestartAcceptRadiiInsideTheClassOnly) {
  const SceneConfig s = parse_scene(normal_drum(kNormal), "normal.toml");
  ParticleTable table;
  table.position = {Vec3(0.0, -0.02, 0.01), Vec3(0.01, -0.02, 0.01)};
  table.radius = {1.5e-3, 2.5e-3};
  table.line = {2, 3};
  const Particles p = particles_from_table(s, table, "pack.csv");
  EXPECT_EQ(p.radius, table.radius);  // a distribution keeps the file's radii
  EXPECT_FALSE(restart_particles_problem(s, p).has_value());

  table.radius[1] = 2.7e-3;  // above 2 mm + 3 sigma
  try {
    particles_from_table(s, table, "pack.csv");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("pack.csv:3: radius 0.0027 m", 0), 0u) << e.what();
  }
  Particles far = p;
  far.radius[0] = 1.3e-3;
  const auto problem = restart_particles_problem(s, far);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->key, "particles/radius: row 0");
}

TEST(SizeDistributionScene, BadKeysAreOneLineNamingFileAndKey) {
  struct Case {
    std::string keys, key;
  };
  const Case cases[] = {
      {"radius = 2e-3\nradius_sigma = 2e-4", "particles[0].radius_sigma"},
      {"distribution = \"gamma\"\nradius = 2e-3", "particles[0].distribution"},
      {"distribution = \"normal\"\nradius = 2e-3\nradius_sigma = -2e-4",
       "particles[0].radius_sigma"},
      {"distribution = \"normal\"\nradius = 2e-3", "particles[0].radius_sigma"},
      {"distribution = \"normal\"\nradius = 2e-3\nradius_sigma = 1e-3",
       "particles[0].radius_sigma"},  // 2 mm - 3 sigma < 0
      {"distribution = \"lognormal\"\nradius = 2e-3\nradius_sigma = 1e-3\ntruncate = 0",
       "particles[0].truncate"},
      {"distribution = \"table\"\nradii = [1e-3, 2e-3]\nshares = [1]", "particles[0].shares"},
      {"distribution = \"table\"\nradii = [1e-3, -2e-3]\nshares = [1, 1]", "particles[0].radii[1]"},
      {"distribution = \"table\"\nradii = [1e-3]\nshares = [0]", "particles[0].shares[0]"},
      {"distribution = \"table\"\nradius = 2e-3\nradii = [1e-3]\nshares = [1]",
       "particles[0].radius"},
      {"radius = 2e-3\nradii = [1e-3]", "particles[0].radii"},
      {"distribution = \"table\"\nshares = [1]", "particles[0].radii"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.keys);
    std::string message;
    try {
      parse_scene(normal_drum(c.keys), "bad.toml");
    } catch (const InputError& e) {
      message = e.what();
    }
    EXPECT_EQ(message.rfind("bad.toml: " + c.key + ":", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(SizeDistributionScene, InfoShowsTheDistributionAndTheBinsAndABadKeyExitsTwo) {
  TempDir dir("size-distribution");
  const auto scene = dir.path() / "normal.toml";
  std::ofstream(scene) << normal_drum(kNormal, "mlgrid");
  const CliResult info = run_cli("info " + scene.string());
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("normal: mean 0.002 m"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("r in [0.0014, 0.0026] m"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("levels by factors of 2"), std::string::npos) << info.output;
  const auto bad = dir.path() / "bad.toml";
  std::ofstream(bad) << normal_drum("radius = 2e-3\nradius_sigma = 2e-4");
  const CliResult r = run_cli("info " + bad.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("particles[0].radius_sigma"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace drumlab::test
