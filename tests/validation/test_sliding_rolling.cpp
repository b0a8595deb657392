// A sphere on a flat floor: Coulomb sliding turning into rolling, and rolling resistance.
// The floor is the end cap at z = H of a drum at rest tilted by 90 degrees, so that gravity in the
// drum frame points along +z onto that cap.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "engine/contact/linear_viscoelastic.hpp"
#include "physics_test_helpers.hpp"

namespace drumlab {
namespace {

constexpr double kR = 0.01;
constexpr double kG = 9.81;

struct Floor {
  SceneConfig scene;
  Particles particles;
};

Floor floor_scene(double mu, double mu_r, const Vec3& v0, const Vec3& w0) {
  Floor f;
  SceneConfig& s = f.scene;
  s = test::make_scene(kR);
  s.gravity = Vec3(0.0, -kG, 0.0);
  s.drum = DrumConfig{4.0, 0.2, 0.0, 0.5 * std::numbers::pi, DrumEnds::caps, {}};
  s.material.friction = mu;
  s.wall.friction = mu;
  s.wall.rolling_friction = mu_r;
  s.material.restitution = 0.3;
  s.wall.restitution = 0.3;
  // Start at the static Hertz overlap mg = 4/3 E* sqrt(r) delta^{3/2} so nothing bounces.
  const double m = s.material.density * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
  const double e_star = s.material.youngs_modulus / (1.0 - 0.09);  // particle vs same wall
  const double delta = std::pow(m * kG / (4.0 / 3.0 * 0.5 * e_star * std::sqrt(kR)), 2.0 / 3.0);
  f.particles.add(Vec3(-1.0, 0.0, 0.2 - kR + delta), kR, s.material.density);
  f.particles.velocity[0] = v0;
  f.particles.omega[0] = w0;
  return f;
}

// Sliding with mu: v(t) = v0 - mu g t until the contact point stops slipping at
// t_r = 2 v0 / (7 mu g); then it rolls at 5/7 v0 with omega_y = -v / r. Tolerances: 1 % on the
// sliding velocity at t_r / 2 and on the final velocity, 1 % on the rolling condition.
TEST(FloorContact, SlidingSphereStartsRollingAtFiveSevenths) {
  const double mu = 0.3, v0 = 1.0;
  Floor f = floor_scene(mu, 0.0, Vec3(v0, 0, 0), Vec3::Zero());
  Simulation sim(f.scene, std::move(f.particles));
  const double t_r = 2.0 * v0 / (7.0 * mu * kG);
  sim.advance(static_cast<std::uint64_t>(0.5 * t_r / sim.dt()));
  const double v_half = sim.particles().velocity[0].x();
  const double expected_half = v0 - mu * kG * sim.time();
  sim.advance(static_cast<std::uint64_t>(2.0 * t_r / sim.dt()));
  const Vec3 v = sim.particles().velocity[0];
  const Vec3 w = sim.particles().omega[0];
  std::printf(
      "sliding: v(%.4f s) = %.5f (expected %.5f); after rolling v = %.5f (5/7 v0 = "
      "%.5f), omega_y r = %.5f\n",
      0.5 * t_r, v_half, expected_half, v.x(), 5.0 / 7.0 * v0, w.y() * kR);
  EXPECT_NEAR(v_half, expected_half, 0.01 * expected_half);
  EXPECT_NEAR(v.x(), 5.0 / 7.0 * v0, 0.01 * 5.0 / 7.0 * v0);
  EXPECT_NEAR(-w.y() * kR, v.x(), 0.01 * v.x());
  EXPECT_NEAR(v.y(), 0.0, 1e-9);
}

// Rolling resistance: a ball rolling without slip decelerates at 5/7 mu_r g (the torque
// mu_r r N acts against rolling; friction keeps it rolling) and stops at t = 7 v0 / (5 mu_r g).
// Tolerance 1 % on the velocity after 0.5 s; after the stop it stays at rest (regularised torque,
// no chatter): speed below 1e-6 m/s and |omega| below 1e-6 rad/s.
TEST(FloorContact, RollingResistanceDeceleratesAtFiveSeventhsMuRG) {
  const double mu_r = 0.05, v0 = 0.5;
  Floor f = floor_scene(0.5, mu_r, Vec3(v0, 0, 0), Vec3(0, -v0 / kR, 0));
  Simulation sim(f.scene, std::move(f.particles));
  sim.advance(static_cast<std::uint64_t>(0.5 / sim.dt()));
  const double v = sim.particles().velocity[0].x();
  const double expected = v0 - 5.0 / 7.0 * mu_r * kG * sim.time();
  const double t_stop = 7.0 * v0 / (5.0 * mu_r * kG);
  sim.advance(static_cast<std::uint64_t>((t_stop + 0.5 - sim.time()) / sim.dt()));
  std::printf(
      "rolling resistance: v(0.5 s) = %.5f (expected %.5f); after the stop v = %.2e, "
      "|omega| = %.2e\n",
      v, expected, sim.particles().velocity[0].norm(), sim.particles().omega[0].norm());
  EXPECT_NEAR(v, expected, 0.01 * expected);
  EXPECT_LT(sim.particles().velocity[0].norm(), 1e-6);
  EXPECT_LT(sim.particles().omega[0].norm(), 1e-6);
}

// The rolling spring ([contact] rolling = "spring", MercuryDPM's law) on the same floor with the
// linear viscoelastic law: once the spring reaches its Coulomb limit the torque is
// mu_r |F_n| 2 r, twice the constant torque's mu_r r |F_n|, so the ball decelerates at
// 5/7 (2 mu_r) g, as the constant torque with 2 mu_r does. Tolerance 1 % on v(0.3 s) against that
// and against the constant-torque run (the spring loads within a few steps); after the stop the
// spring holds the ball: speed below 1e-4 m/s.
TEST(FloorContact, RollingSpringDeceleratesAsTheConstantTorqueOfTwiceMuR) {
  const double mu_r = 0.05, v0 = 0.5;
  const auto run = [&](RollingLaw law, double mu, double seconds) {
    Floor f = floor_scene(0.5, mu, Vec3(v0, 0, 0), Vec3(0, -v0 / kR, 0));
    SceneConfig& s = f.scene;
    s.contact.normal = NormalLaw::linear_viscoelastic;
    s.contact.collision_time = 2e-3;
    s.contact.reference_radius = kR;
    s.contact.rolling = law;
    s.time.dt = 1e-4;
    const double m = s.material.density * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
    const auto normal = LinearViscoelastic::from_collision(2e-3, 0.3, m, 2.0 / 7.0, 2.0 / 7.0);
    f.particles.position[0].z() = 0.2 - kR + m * kG / normal.stiffness;  // static overlap
    Simulation sim(s, std::move(f.particles));
    sim.advance(static_cast<std::uint64_t>(seconds / sim.dt()));
    return std::pair(sim.particles().velocity[0], sim.time());
  };
  const auto [v_spring, t] = run(RollingLaw::spring, mu_r, 0.3);
  const auto [v_torque, t2] = run(RollingLaw::constant_torque, 2.0 * mu_r, 0.3);
  const double expected = v0 - 5.0 / 7.0 * 2.0 * mu_r * kG * t;
  const double t_stop = 7.0 * v0 / (5.0 * 2.0 * mu_r * kG);
  const Vec3 v_end = run(RollingLaw::spring, mu_r, t_stop + 0.5).first;
  std::printf(
      "rolling spring: v(0.3 s) = %.5f (constant torque 2 mu_r: %.5f, expected %.5f); "
      "after the stop v = %.2e\n",
      v_spring.x(), v_torque.x(), expected, v_end.norm());
  EXPECT_NEAR(v_spring.x(), expected, 0.01 * expected);
  EXPECT_NEAR(v_spring.x(), v_torque.x(), 0.01 * expected);
  EXPECT_EQ(t, t2);
  EXPECT_LT(v_end.norm(), 1e-4);
}

}  // namespace
}  // namespace drumlab
