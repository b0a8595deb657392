// The rolling spring composed into ContactModel ([contact] rolling = "spring"): the wall loop and
// the pair loop against the closed form of MercuryDPM's law (rolling_spring.hpp), the state it
// keeps, and its scene keys.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <variant>

#include "engine/contact/contact_model.hpp"
#include "engine/drum.hpp"
#include "engine/scene/scene_validation.hpp"
#include "engine/simulation.hpp"

namespace drumlab {
namespace {

constexpr double kR = 2e-3;
constexpr double kDt = 7e-5;
constexpr double kMuR = 0.5;

SceneConfig spring_scene() {
  SceneConfig s;
  s.name = "rolling spring";
  s.search_method = "brute";
  s.gravity = Vec3::Zero();
  s.classes = {ParticleClass{"grain", kR, 1.0}};
  s.material = Material{1500.0, 5e6, 0.3, 0.5, 0.0, kMuR};
  s.wall = s.material;
  s.contact.normal = NormalLaw::linear_viscoelastic;
  s.contact.collision_time = 0.1 * std::sqrt(kR / 9.8);
  s.contact.reference_radius = kR;
  s.contact.rolling = RollingLaw::spring;
  s.drum = DrumConfig{0.08, 0.01, 0.0, 0.0, DrumEnds::caps, {}};
  return s;
}

// A sphere pressed into the mantle's lowest point (normal into it: +y) turning at w about z
// against the drum at rest: the spring grows by v_r dt a step, v_r = -2 r n x w, until the
// Coulomb limit mu_r |F_n|; the torque is 2 r n x (-k_r xi - gamma_r v_r) and resists the spin.
TEST(RollingSpringModel, WallSpringGrowsThenStopsAtTheCoulombLimit) {
  const SceneConfig s = spring_scene();
  const ContactModel model(s);
  ASSERT_TRUE(model.wall_rolling_spring());
  EXPECT_EQ(model.pair_state_size(), kRollingStateSize);
  const auto& normal = std::get<LinearViscoelastic>(model.wall_normal());
  const double k_r = 2.0 / 7.0 * normal.stiffness;
  const double g_r = 2.0 / 7.0 * normal.damping_coefficient;
  const Drum drum(s.drum);
  Particles p;
  const double delta = 1e-5;
  p.add(Vec3(0.0, -(drum.radius() - kR + delta), 0.005), kR, s.material.density);
  for (const std::string_view name : model.particle_arrays(kWallParts)) p.add_array(name, 0.0);
  p.omega[0] = Vec3(0.0, 0.0, 1.0);
  WallHistory history(1, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  const std::vector<Index> candidate = {0};
  const Vec3 n(0.0, 1.0, 0.0);
  const Vec3 v_r = -2.0 * kR * n.cross(p.omega[0]);
  const double fn = normal.stiffness * delta;  // at rest: no damping
  const double limit = kMuR * fn;
  std::size_t capped = 0;
  for (int step = 1; step <= 100; ++step) {
    p.clear_forces();
    ASSERT_EQ(model.add_wall_forces(p, candidate, drum, 0.0, history, kDt, kDt), 1u);
    EXPECT_NEAR(p.force[0].y(), fn, 1e-9 * fn);
    const Vec3 xi(p.find_array(kWallRollingArrays[0][0])->at(0),
                  p.find_array(kWallRollingArrays[0][1])->at(0),
                  p.find_array(kWallRollingArrays[0][2])->at(0));
    const Vec3 spring = step * kDt * v_r;
    const Vec3 f = -k_r * spring - g_r * v_r;
    const Vec3 torque = p.torque[0];
    EXPECT_LT(torque.z(), 0.0) << step;  // against the spin
    if (f.norm() <= limit) {
      EXPECT_NEAR((xi - spring).norm(), 0.0, 1e-12 * spring.norm()) << step;
      EXPECT_NEAR((torque - 2.0 * kR * n.cross(f)).norm(), 0.0, 1e-9 * torque.norm()) << step;
    } else {
      ++capped;
      EXPECT_NEAR(torque.norm(), 2.0 * kR * limit, 1e-9 * torque.norm()) << step;
      // The spring is where spring and dashpot give the limit.
      EXPECT_NEAR((-k_r * xi - g_r * v_r).norm(), limit, 1e-9 * limit) << step;
    }
  }
  EXPECT_GT(capped, 20u);
  // Lifted off the wall: the spring is reset, as the sliding one.
  p.position[0].y() += 2.0 * delta;
  p.clear_forces();
  model.add_wall_forces(p, candidate, drum, 0.0, history, kDt, kDt);
  EXPECT_EQ(p.find_array(kWallRollingArrays[0][0])->at(0), 0.0);
  EXPECT_EQ(p.torque[0], Vec3::Zero());
}

// Two spheres in contact (normal towards 0: +x), 0 spinning: the pair's spring is the last three
// scalars of its contact state; the torques on the two are opposite; a re-ordering that swaps the
// pair moves the spring without negating it (the sliding history is negated).
TEST(RollingSpringModel, PairSpringLivesInTheContactStateAndIsNotNegatedBySwapping) {
  const SceneConfig s = spring_scene();
  const ContactModel model(s);
  const auto& normal = std::get<LinearViscoelastic>(model.pair_normal());
  const double r_eff = 0.5 * kR;
  Particles p;
  const double delta = 1e-5;
  p.add(Vec3(2.0 * kR - delta, 0.0, 0.0), kR, s.material.density);
  p.add(Vec3::Zero(), kR, s.material.density);
  p.omega[0] = Vec3(0.0, 0.0, 2.0);
  ContactList contacts;
  contacts.set_state_size(model.pair_state_size());
  const std::vector<IndexPair> pair = {{0, 1}};
  contacts.update(pair, 2);
  PairForceBuffers buffers;
  p.clear_forces();
  model.add_pair_forces(p, contacts, buffers, 0.0, kDt, kDt);
  const Vec3 n(1.0, 0.0, 0.0);
  const Vec3 v_r = -2.0 * r_eff * n.cross(p.omega[0]);
  const double* xi = contacts.find_state(0, 1);
  ASSERT_NE(xi, nullptr);
  const Vec3 spring(xi[0], xi[1], xi[2]);
  EXPECT_NEAR((spring - kDt * v_r).norm(), 0.0, 1e-12 * spring.norm());
  const Vec3 f =
      -(2.0 / 7.0) * normal.stiffness * spring - (2.0 / 7.0) * normal.damping_coefficient * v_r;
  EXPECT_NEAR((p.torque[0] - 2.0 * r_eff * n.cross(f)).norm(), 0.0, 1e-9 * p.torque[0].norm());
  EXPECT_EQ(p.torque[0], -p.torque[1]);
  EXPECT_LT(p.torque[0].z(), 0.0);
  contacts.history()[0] = Vec3(1.0, 2.0, 3.0);
  const std::vector<Index> swap = {1, 0};
  contacts.renumber(swap);
  const double* moved = contacts.find_state(0, 1);
  EXPECT_EQ(Vec3(moved[0], moved[1], moved[2]), spring);
  EXPECT_EQ(*contacts.find(0, 1), Vec3(-1.0, -2.0, -3.0));
}

// The constant torque stays the default and keeps no state; the keys are checked at the scene's
// one validation seam.
TEST(RollingSpringModel, DefaultKeepsNoStateAndTheKeysAreValidated) {
  SceneConfig s = spring_scene();
  s.contact.rolling = RollingLaw::constant_torque;
  const ContactModel model(s);
  EXPECT_FALSE(model.pair_rolling_spring());
  EXPECT_EQ(model.pair_state_size(), 0u);
  EXPECT_TRUE(model.particle_arrays(kWallParts).empty());
  s.contact.rolling = RollingLaw::spring;
  s.contact.normal = NormalLaw::hertz;
  const auto problem = scene_problem(s);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->key, "contact.rolling");
  s = spring_scene();
  s.contact.rolling_stiffness_ratio = 0.0;
  ASSERT_TRUE(scene_problem(s).has_value());
  EXPECT_EQ(scene_problem(s)->key, "contact.rolling_stiffness_ratio");
  s = spring_scene();
  s.contact.rolling_damping_ratio = -1.0;
  ASSERT_TRUE(scene_problem(s).has_value());
  EXPECT_EQ(scene_problem(s)->key, "contact.rolling_damping_ratio");
}

// A restart from the state of a run with the spring (pair state and wall arrays) continues it bit
// for bit, with re-orderings on the way.
TEST(RollingSpringModel, RestartContinuesBitForBit) {
  SceneConfig s = spring_scene();
  s.gravity = Vec3(0.0, -9.8, 0.0);
  s.time.dt = kDt;
  s.performance.sort_every = 7;
  Particles p;
  for (int k = 0; k < 6; ++k) {
    const double x = -0.01 + 0.0039 * k;  // neighbours overlap; odd ones press into the mantle
    const double rho = 0.04 - kR + 1e-5 * (k % 2);
    p.add(Vec3(x, -std::sqrt(rho * rho - x * x), 0.005), kR, s.material.density);
    p.omega.back() = Vec3(0.0, 0.0, 3.0 * (k - 2));
  }
  Simulation a(s, p);
  a.advance(60);
  Simulation b(s, a.state());
  a.advance(60);
  b.advance(60);
  EXPECT_EQ(a.particles().position, b.particles().position);
  EXPECT_EQ(a.particles().omega, b.particles().omega);
}

}  // namespace
}  // namespace drumlab
