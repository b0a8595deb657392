// A particle resting on the wall of a turning drum is carried up by friction in the sense of the
// rotation; without friction the wall cannot drag it at all.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics_test_helpers.hpp"

namespace drumlab {
namespace {

struct Carried {
  double angle = 0.0;  ///< rad from the bottom, positive in the drum's rotation sense
  double spin = 0.0;   ///< omega_z of the particle, rad/s
};

// Drum D = 0.2 m turning at +2 rad/s about +z; a 1 cm particle starts touching the bottom of the
// cylinder (0, -R + r) half way between the caps. At the bottom the wall moves towards +x, so the
// angle from the bottom is atan2(x, -y).
Carried carry(double friction, double seconds) {
  const double r = 0.01;
  SceneConfig s = test::make_scene(r);
  s.gravity = Vec3(0.0, -9.81, 0.0);
  s.drum = DrumConfig{0.2, 0.1, 2.0, 0.0, DrumEnds::caps, {}};
  s.wall.friction = friction;
  s.material.friction = friction;
  s.material.restitution = 0.5;
  s.wall.restitution = 0.5;
  Particles p;
  p.add(Vec3(0.0, -0.1 + r, 0.05), r, s.material.density);
  Simulation sim(s, std::move(p));
  sim.advance(static_cast<std::uint64_t>(std::lround(seconds / sim.dt())));
  const Vec3& x = sim.particles().position[0];
  return {std::atan2(x.x(), -x.y()), sim.particles().omega[0].z()};
}

// Analytical estimate for mu = 0.5. While the contact slips, friction mu m g accelerates the
// centre (dv/dt = mu g) and spins the ball (r domega/dt = 5/2 mu g) until the contact point moves
// with the wall, V = Omega R, at t_s = 2 V / (7 mu g). Then the ball rolls without slip and, since
// the wall speed is constant, its angle obeys 7/5 L theta'' = -g sin theta (L = R - r): a pendulum
// of frequency W = sqrt(5 g / (7 L)) started at theta_s = mu g t_s^2 / (2 L) with rate mu g t_s /
// L. Small-angle solution at 0.2 s: 0.07132 rad; measured 0.07155 rad (+0.3 %: the estimate ignores
// the Hertz/Mindlin compliance and the small settling bounce). Tolerance 2 %. The ball must also
// spin in the drum's sense (omega_z > 0).
// With mu = 0 no tangential force exists: the particle stays exactly at the bottom (x == 0) and
// does not spin. Tolerance 1e-12 rad.
TEST(WallFriction, RotatingWallCarriesAParticleUpOnlyWithFriction) {
  const double g = 9.81, mu = 0.5, big_r = 0.1, r = 0.01, omega = 2.0, t = 0.2;
  const double t_s = 2.0 * omega * big_r / (7.0 * mu * g);
  const double len = big_r - r;
  const double w = std::sqrt(5.0 * g / (7.0 * len));
  const double expected = 0.5 * mu * g * t_s * t_s / len * std::cos(w * (t - t_s)) +
                          mu * g * t_s / (len * w) * std::sin(w * (t - t_s));
  const Carried with = carry(mu, t);
  const Carried without = carry(0.0, t);
  std::printf(
      "mu = 0.5: angle %.5f rad (estimate %.5f), spin %.4f rad/s; mu = 0: angle %.3e rad, "
      "spin %.3e\n",
      with.angle, expected, with.spin, without.angle, without.spin);
  EXPECT_NEAR(with.angle, expected, 0.02 * expected);
  EXPECT_GT(with.spin, 0.0);
  EXPECT_LT(std::abs(without.angle), 1e-12);
  EXPECT_EQ(without.spin, 0.0);
}

}  // namespace
}  // namespace drumlab
