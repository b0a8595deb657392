// Accretion onto a seed (engine/analysis/accretion.hpp) and the per-class liquid content that sets
// it up: the count of primaries held in the seeds' granules on hand-built frames; the saturating
// exponential recovered from its own values and from noisy ones; a class's liquid_content filling
// that class's films only; the loader and the validation of the key.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "engine/analysis/accretion.hpp"
#include "engine/contact/bond.hpp"
#include "engine/scene/scene_validation.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

constexpr double kPi = std::numbers::pi;

// Particles 0..6 in three granules: {0, 1, 2, 3} (label 0), {4, 5} (label 4), {6} (label 6).
AgglomerateFrame three_granules() {
  AgglomerateFrame f;
  f.label = {0, 0, 0, 0, 4, 4, 6};
  f.size_of = {4, 4, 4, 4, 2, 2, 1};
  return f;
}

TEST(Accretion, CountsThePrimariesInTheSeedsGranulesLessTheSeeds) {
  const AgglomerateFrame f = three_granules();
  // One seed (class 1) in the granule of four: three accreted.
  EXPECT_EQ(accreted_count(f, std::vector<std::uint8_t>{0, 1, 0, 0, 0, 0, 0}, 1), 3u);
  // Two seeds in that granule: each granule counted once, both seeds taken off.
  EXPECT_EQ(accreted_count(f, std::vector<std::uint8_t>{1, 1, 0, 0, 0, 0, 0}, 1), 2u);
  // A seed alone holds nothing; with another seed in the pair, the pair's partner counts.
  EXPECT_EQ(accreted_count(f, std::vector<std::uint8_t>{0, 0, 0, 0, 0, 0, 1}, 1), 0u);
  EXPECT_EQ(accreted_count(f, std::vector<std::uint8_t>{0, 1, 0, 0, 1, 0, 1}, 1), 4u);
  // No particle of the class.
  EXPECT_EQ(accreted_count(f, std::vector<std::uint8_t>(7, 0), 3), 0u);
  EXPECT_THROW(accreted_count(f, std::vector<std::uint8_t>(6, 0), 0), std::invalid_argument);
}

TEST(Accretion, CountsThroughFindAgglomeratesOnAChain) {
  // Five particles in a row, bonds 0-1, 1-2 and 3-4; the seed is particle 1 (class 2).
  const std::vector<Vec3> position = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(5, 0, 0),
                                      Vec3(6, 0, 0)};
  const std::vector<double> radius(5, 0.5), mass(5, 1.0);
  const std::vector<std::uint32_t> id = {0, 1, 2, 3, 4};
  const std::vector<Bond> bonds = {
      {0, 1, 1e-9, 1.0, 1.0}, {1, 2, 1e-9, 1.0, 1.0}, {3, 4, 1e-9, 1.0, 1.0}};
  AgglomerateInput in;
  in.position = position;
  in.radius = radius;
  in.mass = mass;
  in.id = id;
  in.bonds = bonds;
  const AgglomerateFrame f = find_agglomerates(in, AgglomerateOptions{});
  EXPECT_EQ(accreted_count(f, std::vector<std::uint8_t>{0, 2, 0, 0, 0}, 2), 2u);
  EXPECT_EQ(accreted_count(f, std::vector<std::uint8_t>{0, 0, 0, 0, 2}, 2), 1u);
}

std::vector<double> times(std::size_t count, double t0, double step) {
  std::vector<double> t;
  for (std::size_t k = 0; k < count; ++k) t.push_back(t0 + step * static_cast<double>(k));
  return t;
}

TEST(Accretion, TheFitRecoversTheCurveItWasDrawnFrom) {
  const double n0 = 3.0, n_inf = 120.0, tau = 3.5, t0 = 0.5;
  const std::vector<double> t = times(40, t0, 0.25);
  std::vector<double> n;
  for (const double time : t) n.push_back(n_inf - (n_inf - n0) * std::exp(-(time - t0) / tau));
  const SaturatingFit fit = fit_saturating_exponential(t, n);
  EXPECT_NEAR(fit.tau, tau, 1e-6 * tau);
  EXPECT_NEAR(fit.n_inf, n_inf, 1e-6 * n_inf);
  EXPECT_NEAR(fit.n0, n0, 1e-5);
  EXPECT_EQ(fit.t0, t0);
  EXPECT_LT(fit.rms, 1e-6);
  EXPECT_NEAR(fit.r_squared, 1.0, 1e-12);
  EXPECT_LT(fit.line_r_squared, 0.99);  // the curve bends within the window
  EXPECT_FALSE(fit.tau_at_grid_edge);
  EXPECT_NEAR(saturating_value(fit, 2.0), n_inf - (n_inf - n0) * std::exp(-1.5 / tau), 1e-5);
}

TEST(Accretion, TheFitHoldsWithinTheNoiseOfCountedData) {
  // Counts rounded to integers, with a deterministic +-2 wobble: tau within 5 %, N_inf within 2 %.
  const double n0 = 0.0, n_inf = 80.0, tau = 6.0;
  const std::vector<double> t = times(60, 0.0, 0.5);
  std::vector<double> n;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double wobble = (k % 3 == 0) ? 2.0 : (k % 3 == 1 ? -2.0 : 0.0);
    n.push_back(std::round(n_inf - (n_inf - n0) * std::exp(-t[k] / tau)) + wobble);
  }
  const SaturatingFit fit = fit_saturating_exponential(t, n);
  EXPECT_NEAR(fit.tau, tau, 0.05 * tau);
  EXPECT_NEAR(fit.n_inf, n_inf, 0.02 * n_inf);
  EXPECT_GT(fit.r_squared, 0.98);
  EXPECT_GT(fit.r_squared, fit.line_r_squared);
}

TEST(Accretion, AStraightLineRunsTauToTheGridsEdge) {
  const std::vector<double> t = times(20, 1.0, 1.0);
  std::vector<double> n;
  for (const double time : t) n.push_back(5.0 + 2.0 * time);
  const SaturatingFit fit = fit_saturating_exponential(t, n);
  EXPECT_TRUE(fit.tau_at_grid_edge);
  EXPECT_NEAR(fit.line_r_squared, 1.0, 1e-12);
  EXPECT_GT(fit.r_squared, 0.9999);
}

TEST(Accretion, TheFitRefusesWhatItCannotFit) {
  const std::vector<double> two = {0.0, 1.0};
  EXPECT_THROW(fit_saturating_exponential(two, two), std::invalid_argument);
  const std::vector<double> t = {0.0, 1.0, 1.0}, n = {1.0, 2.0, 3.0};
  EXPECT_THROW(fit_saturating_exponential(t, n), std::invalid_argument);
  const std::vector<double> good = {0.0, 1.0, 2.0}, nan = {1.0, std::nan(""), 3.0};
  EXPECT_THROW(fit_saturating_exponential(good, nan), std::invalid_argument);
  EXPECT_THROW(fit_saturating_exponential(good, two), std::invalid_argument);
}

// The small drum with migration (1 % liquid) and its large class given 20 %.
SceneConfig seeded_scene() {
  SceneConfig s = parse_scene(output_scene_text() +
                                  "[liquid]\nsurface_tension = 0.072\nliquid_content = 0.01\n"
                                  "max_bridge_volume = 1e-9\n",
                              "seed.toml");
  s.classes[1].liquid_content = 0.2;
  return s;
}

TEST(Accretion, AClassLiquidContentFillsThatClasssFilmsOnly) {
  const SceneConfig scene = seeded_scene();
  validate(scene, "seed.toml");
  const Particles start = random_fill(scene);
  const Simulation sim(scene, start);
  const Particles& p = sim.particles();
  const std::vector<double>& film = *p.find_array(kLiquidFilmArray);
  std::size_t large = 0;
  double total = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    const double content = p.size_class[i] == 1 ? 0.2 : 0.01;
    large += p.size_class[i] == 1 ? 1 : 0;
    EXPECT_EQ(film[i], content * (4.0 / 3.0) * kPi * r * r * r) << i;
    total += film[i];
  }
  EXPECT_GT(large, 0u);
  EXPECT_NEAR(sim.liquid().total(), total, 1e-12 * total);
}

TEST(Accretion, TheClassKeyIsReadWrittenAndValidated) {
  const std::string wet = output_scene_text() +
                          "[liquid]\nsurface_tension = 0.072\nliquid_content = 0.01\n"
                          "max_bridge_volume = 1e-9\n";
  std::string text = wet;
  const std::string second = "radius = 0.008\n";
  text.replace(text.find(second), second.size(), second + "liquid_content = 0.25\n");
  const SceneConfig s = parse_scene(text, "seed.toml");
  ASSERT_TRUE(s.classes[1].liquid_content.has_value());
  EXPECT_EQ(*s.classes[1].liquid_content, 0.25);
  EXPECT_FALSE(s.classes[0].liquid_content.has_value());

  SceneConfig high = seeded_scene();
  high.classes[1].liquid_content = 1.5;
  auto problem = scene_problem(high);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->key, "particles[1].liquid_content");
  SceneConfig dry = parse_scene(output_scene_text(), "dry.toml");
  dry.classes[0].liquid_content = 0.1;
  problem = scene_problem(dry);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->key, "particles[0].liquid_content");
  EXPECT_NE(problem->reason.find("needs [liquid]"), std::string::npos) << problem->reason;
}

}  // namespace
}  // namespace drumlab::test
