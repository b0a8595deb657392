// Contact laws against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine/contact/hertz_mindlin.hpp"
#include "engine/contact/linear_spring_dashpot.hpp"
#include "engine/contact/linear_viscoelastic.hpp"
#include "engine/contact/rolling_resistance.hpp"
#include "engine/contact/rolling_spring.hpp"

namespace drumlab {
namespace {

Material glass() {
  return Material{2500.0, 5e6, 0.3, 0.5, 0.5, 0.1};
}

TEST(EffectiveModuli, IdenticalMaterials) {
  const Material m = glass();
  EXPECT_NEAR(effective_youngs_modulus(m, m), 5e6 / (2.0 * (1.0 - 0.09)), 1e-6);
  const double g = 5e6 / (2.0 * 1.3);
  EXPECT_NEAR(effective_shear_modulus(m, m), g / (2.0 * (2.0 - 0.3)), 1e-6);
}

TEST(EffectiveModuli, DifferentMaterialsCombineInSeries) {
  const Material a = glass();
  Material b = glass();
  b.youngs_modulus = 2e9;
  b.poisson_ratio = 0.25;
  const double expected = 1.0 / (0.91 / 5e6 + (1.0 - 0.0625) / 2e9);
  EXPECT_NEAR(effective_youngs_modulus(a, b), expected, 1e-6 * expected);
  // A rigid wall leaves the particle's own E / (1 - nu^2).
  b.youngs_modulus = 1e30;
  EXPECT_NEAR(effective_youngs_modulus(a, b), 5e6 / 0.91, 1e-3);
}

TEST(HertzNormal, ElasticForceIsFourThirdsEStarSqrtRDelta32) {
  const HertzNormal h(2.0e6, 1.0e6, 1.0);
  // R* = 0.005 m, delta = 1e-4 m: 4/3 * 2e6 * sqrt(0.005) * 1e-6 = 0.18856180831641267 N.
  EXPECT_NEAR(h.force(1e-4, 0.0, 0.005, 0.01), 0.18856180831641267, 1e-15);
  EXPECT_EQ(h.beta, 0.0);
  EXPECT_EQ(h.force(1e-4, -1.0, 0.005, 0.01), h.force(1e-4, 0.0, 0.005, 0.01));
}

TEST(HertzNormal, DampingFollowsTheTsujiForm) {
  const double e = 0.5;
  const HertzNormal h(2.0e6, 1.0e6, e);
  const double l = std::log(e);
  const double beta = l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
  EXPECT_NEAR(h.beta, beta, 1e-15);
  const double delta = 1e-4, r = 0.005, m = 0.01, vn = -0.3;
  const double s_n = 2.0 * 2.0e6 * std::sqrt(r * delta);
  const double gamma = -2.0 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(s_n * m);
  EXPECT_NEAR(h.force(delta, vn, r, m), 2.0 / 3.0 * s_n * delta - gamma * vn, 1e-12);
  // Approaching (vn < 0) adds repulsion; separating fast enough gives an (unclipped) attraction.
  EXPECT_GT(h.force(delta, vn, r, m), h.force(delta, 0.0, r, m));
  EXPECT_LT(h.force(1e-9, 10.0, r, m), 0.0);
}

TEST(HertzNormal, TangentialStiffnessIsEightGStarSqrtRDelta) {
  const HertzNormal h(2.0e6, 1.0e6, 0.5);
  const TangentialCoefficients c = h.tangential(1e-4, 0.005, 0.01);
  EXPECT_NEAR(c.stiffness, 8.0 * 1.0e6 * std::sqrt(0.005 * 1e-4), 1e-9);
  EXPECT_NEAR(c.damping, -2.0 * std::sqrt(5.0 / 6.0) * h.beta * std::sqrt(c.stiffness * 0.01),
              1e-12);
}

TEST(HertzNormal, ElasticEnergyIsTheIntegralOfTheForce) {
  const HertzNormal h(2.0e6, 1.0e6, 1.0);
  const double d = 2e-4, eps = 1e-9;
  const double numeric =
      (h.elastic_energy(d + eps, 0.005) - h.elastic_energy(d - eps, 0.005)) / (2.0 * eps);
  EXPECT_NEAR(numeric, h.force(d, 0.0, 0.005, 1.0), 1e-6 * h.force(d, 0.0, 0.005, 1.0));
}

TEST(LinearSpringDashpot, ForceAndDampingForExactRestitution) {
  const double k = 1e4, e = 0.5, m = 0.005;
  const LinearSpringDashpot law(k, e);
  const double l = std::log(e);
  const double gamma =
      2.0 * std::sqrt(m * k) * (-l) / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
  EXPECT_NEAR(law.damping(m), gamma, 1e-12);
  EXPECT_NEAR(law.force(1e-4, -0.2, 0.005, m), k * 1e-4 + gamma * 0.2, 1e-12);
  // Not clipped: a separating contact can pull.
  EXPECT_LT(law.force(1e-6, 1.0, 0.005, m), 0.0);
  const double wd = std::sqrt(k / m - std::pow(gamma / (2.0 * m), 2));
  EXPECT_NEAR(law.contact_duration(m), std::numbers::pi / wd, 1e-15);
  EXPECT_NEAR(LinearSpringDashpot(k, 1.0).contact_duration(m), std::numbers::pi * std::sqrt(m / k),
              1e-15);
  EXPECT_NEAR(law.elastic_energy(2e-3, 0.0), 0.5 * k * 4e-6, 1e-15);
  EXPECT_NEAR(law.tangential(0.0, 0.0, m).stiffness, 2.0 / 7.0 * k, 1e-12);
}

// MercuryDPM's setCollisionTimeAndRestitutionCoefficient(t_c, e, m): gamma = -m ln(e) / t_c,
// k = m/2 (pi^2/t_c^2 + (gamma/m)^2); the reference pair (m* = m/2) has exactly t_c and e, a wall
// contact (m* = m) neither; the tangential spring and dashpot are 2/7 of the normal ones.
TEST(LinearViscoelastic, CollisionTimeAndRestitutionSetStiffnessAndDamping) {
  const double t_c = 1.4e-3, e = 0.5, m = 5e-5;
  const auto law = LinearViscoelastic::from_collision(t_c, e, m, 2.0 / 7.0, 2.0 / 7.0);
  const double gamma = -m * std::log(e) / t_c;
  const double k = 0.5 * m * (std::pow(std::numbers::pi / t_c, 2) + std::pow(gamma / m, 2));
  EXPECT_NEAR(law.damping_coefficient, gamma, 1e-14 * gamma);
  EXPECT_NEAR(law.stiffness, k, 1e-14 * k);
  EXPECT_NEAR(law.contact_duration(0.5 * m), t_c, 1e-13 * t_c);
  EXPECT_NEAR(law.restitution(0.5 * m), e, 1e-13);
  // The same k and gamma for a wall contact: a longer contact, a higher restitution.
  const double wd = std::sqrt(k / m - std::pow(gamma / (2.0 * m), 2));
  EXPECT_NEAR(law.contact_duration(m), std::numbers::pi / wd, 1e-13 * t_c);
  EXPECT_NEAR(law.restitution(m), std::exp(-gamma * std::numbers::pi / wd / (2.0 * m)), 1e-13);
  EXPECT_GT(law.restitution(m), e + 0.1);
  // Constant damping: the force does not depend on m*; not clipped.
  EXPECT_DOUBLE_EQ(law.force(1e-5, -0.1, 0.0, m), law.force(1e-5, -0.1, 0.0, 0.1 * m));
  EXPECT_NEAR(law.force(1e-5, -0.1, 0.0, m), k * 1e-5 + gamma * 0.1, 1e-12 * k * 1e-5);
  EXPECT_LT(law.force(1e-9, 0.5, 0.0, m), 0.0);
  const TangentialCoefficients tc = law.tangential(1e-5, 0.0, m);
  EXPECT_DOUBLE_EQ(tc.stiffness, 2.0 / 7.0 * law.stiffness);
  EXPECT_DOUBLE_EQ(tc.damping, 2.0 / 7.0 * law.damping_coefficient);
  EXPECT_NEAR(law.elastic_energy(2e-5, 0.0), 0.5 * k * 4e-10, 1e-12 * k * 4e-10);
  // Elastic (e = 1): no damping, k = m pi^2 / (2 t_c^2).
  const auto elastic = LinearViscoelastic::from_collision(t_c, 1.0, m, 0.4, 0.1);
  EXPECT_EQ(elastic.damping_coefficient, 0.0);
  EXPECT_NEAR(elastic.stiffness, 0.5 * m * std::pow(std::numbers::pi / t_c, 2), 1e-14 * k);
  EXPECT_DOUBLE_EQ(elastic.tangential(0.0, 0.0, m).stiffness, 0.4 * elastic.stiffness);
}

// The peer's own figures: RotatingDrumWet (r = 2 mm, rho = 1500, t_c = 0.1 sqrt(r / g), e = 0.5)
// logs "set stiffness to 127.461 and dissipation to 0.024389" (6 significant digits).
TEST(LinearViscoelastic, MatchesTheMercuryDrumsLoggedStiffnessAndDissipation) {
  const double r = 2e-3, mass = 1500.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const auto law =
      LinearViscoelastic::from_collision(0.1 * std::sqrt(r / 9.8), 0.5, mass, 2.0 / 7.0, 2.0 / 7.0);
  EXPECT_NEAR(law.stiffness, 127.461, 0.0005);
  EXPECT_NEAR(law.damping_coefficient, 0.024389, 0.0000005);
}

// The peer's rolling spring (FrictionInteraction.cc): v_r = -2 R* n x w_rel, xi += v_r dt, F_r =
// -k xi - gamma v_r, torque on i 2 R* n x F_r; at the Coulomb limit |F_r| = mu_r |F_n| and xi
// follows so that spring and dashpot give the limit.
TEST(RollingSpring, StickingSpringAndDashpotThenTheCoulombLimit) {
  const RollingSpring law{200.0, 0.01, 0.5};
  const Vec3 n(0.0, 1.0, 0.0), w(0.0, 0.0, 2.0), none = Vec3::Zero();
  const double r = 2e-3, dt = 1e-5, fn = 1.0;
  const Vec3 v_r = -2.0 * r * n.cross(w);  // (-8e-3, 0, 0)
  EXPECT_NEAR(v_r.x(), -8e-3, 1e-18);
  Vec3 xi = Vec3::Zero();
  const Vec3 m1 = law.torque(xi, n, w, none, 0.0, r, fn, dt);
  EXPECT_NEAR((xi - v_r * dt).norm(), 0.0, 1e-20);
  const Vec3 f1 = -200.0 * xi - 0.01 * v_r;
  EXPECT_NEAR((m1 - 2.0 * r * n.cross(f1)).norm(), 0.0, 1e-18);
  EXPECT_LT(m1.dot(w), 0.0);  // resists the rotation
  // Sticking: the spring grows by v_r dt a step.
  const Vec3 m2 = law.torque(xi, n, w, none, 0.0, r, fn, dt);
  EXPECT_NEAR((xi - 2.0 * dt * v_r).norm(), 0.0, 1e-20);
  EXPECT_NEAR((m2 - 2.0 * r * n.cross(Vec3(-200.0 * xi - 0.01 * v_r))).norm(), 0.0, 1e-18);
  // Past the limit (a large spring): |F_r| = mu_r |F_n|, so |M| = 2 R* mu_r |F_n|, and the spring
  // is what gives that force with the dashpot.
  xi = Vec3(1e-2, 0.0, 0.0);
  const Vec3 m3 = law.torque(xi, n, w, none, 0.0, r, fn, dt);
  EXPECT_NEAR(m3.norm(), 2.0 * r * 0.5 * fn, 1e-15);
  const Vec3 f3 = -200.0 * xi - 0.01 * v_r;
  EXPECT_NEAR(f3.norm(), 0.5 * fn, 1e-12);
  EXPECT_NEAR((m3 - 2.0 * r * n.cross(f3)).norm(), 0.0, 1e-15);
  // Swapping i and j (n and w_rel negated) leaves v_r, the spring and the force as they were: the
  // torque on the other body is the opposite one.
  Vec3 xi_i = Vec3(1e-6, 0.0, 2e-6), xi_j = xi_i;
  const Vec3 mi = law.torque(xi_i, n, w, none, 0.0, r, fn, dt);
  const Vec3 mj = law.torque(xi_j, -n, -w, none, 0.0, r, fn, dt);
  EXPECT_EQ(xi_i, xi_j);
  EXPECT_NEAR((mi + mj).norm(), 0.0, 1e-18);
  // The pair's objective correction: - (xi . v_ij) n / |d| dt.
  Vec3 xc = Vec3(1e-6, 0.0, 0.0);
  const Vec3 v_ij(0.5, 0.0, 0.0);
  law.torque(xc, n, Vec3::Zero(), v_ij, 1.0 / (2.0 * r), r, fn, dt);
  EXPECT_NEAR((xc - Vec3(1e-6, -1e-6 * 0.5 / (2.0 * r) * dt, 0.0)).norm(), 0.0, 1e-20);
}

TEST(MindlinTangential, StickingSpringAccumulatesDisplacement) {
  const MindlinTangential t{0.5};
  const TangentialCoefficients c{1000.0, 0.0};
  const Vec3 n(0.0, 0.0, 1.0);
  Vec3 xi = Vec3::Zero();
  const Vec3 vt(0.01, 0.0, 0.0);
  Vec3 f = Vec3::Zero();
  for (int k = 0; k < 10; ++k) f = t.force(xi, n, vt, c, 10.0, 1e-3);
  EXPECT_NEAR(xi.x(), 1e-4, 1e-15);
  EXPECT_NEAR(f.x(), -0.1, 1e-12);  // -k_t xi, well below mu F_n = 5 N
  EXPECT_NEAR(f.y(), 0.0, 1e-15);
}

TEST(MindlinTangential, CoulombLimitCapsTheForceAndRescalesTheSpring) {
  const MindlinTangential t{0.5};
  const TangentialCoefficients c{1000.0, 2.0};
  const Vec3 n(0.0, 0.0, 1.0);
  Vec3 xi(0.02, 0.01, 0.0);  // spring force 22 N, limit 0.5 * 10 N
  const Vec3 vt(0.1, -0.2, 0.0);
  const Vec3 f = t.force(xi, n, vt, c, 10.0, 1e-3);
  EXPECT_NEAR(f.norm(), 5.0, 1e-12);
  // Direction of the trial force, and the spring now gives exactly the limit force.
  const Vec3 trial = -1000.0 * (Vec3(0.02, 0.01, 0.0) + 1e-3 * vt) - 2.0 * vt;
  EXPECT_NEAR((f.normalized() - trial.normalized()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((-c.stiffness * xi - c.damping * vt - f).norm(), 0.0, 1e-12);
}

TEST(MindlinTangential, HistoryIsRotatedIntoTheNewTangentPlaneKeepingItsLength) {
  const MindlinTangential t{10.0};
  const TangentialCoefficients c{1000.0, 0.0};
  Vec3 xi(1e-4, 0.0, 0.0);  // tangent to the old normal z
  const double a = 0.1;
  const Vec3 n(std::sin(a), 0.0, std::cos(a));  // the contact turned by 0.1 rad about y
  t.force(xi, n, Vec3::Zero(), c, 100.0, 1e-3);
  EXPECT_NEAR(xi.dot(n), 0.0, 1e-18);
  EXPECT_NEAR(xi.norm(), 1e-4, 1e-18);
  EXPECT_NEAR(xi.x(), 1e-4 * std::cos(a), 1e-18);
}

TEST(RollingResistance, ConstantTorqueOpposesRelativeRotation) {
  const RollingResistance roll{0.1};
  const Vec3 w(0.0, 3.0, 4.0);
  const Vec3 m = roll.torque(w, 2.0, 0.005, 1e-6);
  EXPECT_NEAR(m.norm(), 0.1 * 0.005 * 2.0, 1e-15);  // mu_r R* |F_n|
  EXPECT_NEAR((m.normalized() + w.normalized()).norm(), 0.0, 1e-15);
}

TEST(RollingResistance, RegularisedBelowTheRateTheTorqueStopsInOneStep) {
  const RollingResistance roll{0.1};
  const double m_max = 0.1 * 0.005 * 2.0;
  const double stop_rate = 10.0;  // dt (1/I_i + 1/I_j)
  const double w0 = m_max * stop_rate;
  const Vec3 slow(0.25 * w0, 0.0, 0.0);
  const Vec3 m = roll.torque(slow, 2.0, 0.005, stop_rate);
  EXPECT_NEAR(m.x(), -0.25 * m_max, 1e-15);               // linear in omega_rel
  EXPECT_NEAR(slow.x() + m.x() * stop_rate, 0.0, 1e-15);  // one step removes it exactly
  // Continuous at the threshold, and zero at rest.
  EXPECT_NEAR(roll.torque(Vec3(w0 * (1 + 1e-12), 0, 0), 2.0, 0.005, stop_rate).x(), -m_max, 1e-12);
  EXPECT_NEAR(roll.torque(Vec3(w0 * (1 - 1e-12), 0, 0), 2.0, 0.005, stop_rate).x(), -m_max, 1e-12);
  EXPECT_EQ(roll.torque(Vec3::Zero(), 2.0, 0.005, stop_rate), Vec3::Zero());
}

}  // namespace
}  // namespace drumlab
