// The overlap stop of a soft, strongly cohesive bed (issue 40): a large sphere falling at 3 m/s
// onto a small one that rests on the drum mantle, as a 15 mm particle does in the demo drum with
// sjkr k_c = 1.5e5 once the wall's adhesion has carried it over the top (engine/README.md,
// "When a run stops"). The impact itself, resolved by the step, overlaps the small sphere by more
// than half its radius: the stop names the bodies, their speed, time.max_overlap and what helps,
// a smaller dt gives the same overlap, and a larger time.max_overlap lets the run go on.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "physics_test_helpers.hpp"

namespace drumlab {
namespace {

constexpr double kSmall = 0.005;
constexpr double kLarge = 0.015;

SceneConfig cohesive_drum(double dt) {
  SceneConfig s = test::make_scene(kSmall);
  s.classes = {ParticleClass{"small", kSmall, 0.5}, ParticleClass{"large", kLarge, 0.5}};
  s.material.friction = 0.5;
  s.wall = s.material;
  s.gravity = Vec3(0.0, -9.81, 0.0);
  s.drum = DrumConfig{0.2, 0.04, 0.0, 0.0, DrumEnds::caps, {}};
  s.cohesion = CohesionConfig{true, 1.5e5};
  s.time.dt = dt;
  s.output.diagnostics_every = 5;
  return s;
}

/// The small sphere (id 0) on the bottom of the mantle, the large one (id 1) just above it,
/// falling at 3 m/s.
Particles impact() {
  Particles p;
  const double y_small = -0.1 + kSmall;
  p.add(Vec3(0.0, y_small, 0.02), kSmall, 2500.0, 0);
  p.add(Vec3(0.0, y_small + kSmall + kLarge + 1e-4, 0.02), kLarge, 2500.0, 1);
  p.velocity[1] = Vec3(0.0, -3.0, 0.0);
  return p;
}

/// Runs the impact for 10 ms (its peak: 3 ms); returns the stop's message (empty if none) and the
/// largest overlap ratio seen at the checks.
std::pair<std::string, double> run_impact(const SceneConfig& s) {
  Simulation sim(s, impact());
  double peak = 0.0;
  const auto steps = static_cast<std::uint64_t>(0.01 / *s.time.dt);
  try {
    for (std::uint64_t k = 0; k < steps; ++k) {
      sim.step();
      peak = std::max(peak, sim.diagnostics().max_overlap_ratio);
      if (sim.steps() % s.output.diagnostics_every == 0) sim.check_stability();
    }
  } catch (const UnstableError& e) {
    return {e.what(), peak};
  }
  return {"", peak};
}

TEST(ImpactStop, NamesTheBodiesTheSpeedAndTheKeys) {
  const auto [msg, peak] = run_impact(cohesive_drum(1e-4));
  ASSERT_FALSE(msg.empty()) << "no stop; peak overlap " << peak;
  EXPECT_GT(peak, 0.5);
  for (const char* part :
       {"overlap of ", "(limit time.max_overlap = 0.5)", "particles 0 and 1 (radii 5 and 15 mm)",
        "meeting at ", "the step resolves this impact", "time.dt (now 0.0001 s",
        "material.youngs_modulus", "cohesion.energy_density"}) {
    EXPECT_NE(msg.find(part), std::string::npos) << part << "\n" << msg;
  }
}

TEST(ImpactStop, ASmallerTimeStepGivesTheSameOverlapALargerLimitRunsOn) {
  EXPECT_FALSE(run_impact(cohesive_drum(5e-5)).first.empty());
  SceneConfig s1 = cohesive_drum(1e-4);
  SceneConfig s2 = cohesive_drum(5e-5);
  s1.time.max_overlap = s2.time.max_overlap = 0.9;
  const auto [msg_1, peak_1] = run_impact(s1);
  const auto [msg_2, peak_2] = run_impact(s2);
  EXPECT_TRUE(msg_1.empty()) << msg_1;
  EXPECT_TRUE(msg_2.empty()) << msg_2;
  EXPECT_GT(peak_1, 0.5);
  // 0.831 and 0.831 radii, 1e-4 apart
  EXPECT_NEAR(peak_2, peak_1, 0.01 * peak_1) << "the impact's overlap, not the step's";
}

}  // namespace
}  // namespace drumlab
