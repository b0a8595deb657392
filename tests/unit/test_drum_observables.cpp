// Drum observables and the regime classifier on synthetic particle sets with known answers.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

#include "engine/analysis/drum_observables.hpp"
#include "engine/analysis/flow_regime.hpp"

namespace drumlab {
namespace {

constexpr double kPi = std::numbers::pi;

/// A bed on a touching cubic lattice (spacing 2r) filling the part of a drum of radius R below
/// the plane u = c + tan(theta) h, written in the cross-section axes (up, carry). Velocities:
/// `flow` m/s downhill along the plane at the surface, falling linearly to zero at depth
/// `layer` below the plane and uphill below it.
struct SlabSpec {
  double radius_drum = 0.2;
  double r = 0.002;
  double depth = 0.02;
  double theta_deg = 30.0;
  double c = -0.05;
  double layer = 0.03;
  double flow = 0.5;
  Vec3 up = Vec3::UnitY();
  Vec3 carry = Vec3::UnitX();
};

Particles tilted_slab(const SlabSpec& s) {
  Particles p;
  const double step = 2.0 * s.r;
  const double tan_t = std::tan(s.theta_deg * kPi / 180.0);
  const double len = std::sqrt(1.0 + tan_t * tan_t);
  const Vec3 downhill = -(s.carry + tan_t * s.up) / len;
  const double reach = s.radius_drum - s.r;
  for (double h = -reach; h <= reach; h += step) {
    for (double u = -reach; u <= reach; u += step) {
      if (h * h + u * u > reach * reach || u + s.r > s.c + tan_t * h) continue;
      const double depth_below = (s.c + tan_t * h - u) / len;
      for (double z = s.r; z <= s.depth - s.r + 1e-12; z += step) {
        const Index i = p.add(h * s.carry + u * s.up + z * Vec3::UnitZ(), s.r, 2500.0);
        p.velocity[i] = s.flow * (1.0 - depth_below / s.layer) * downhill;
      }
    }
  }
  return p;
}

DrumGeometry geometry(const SlabSpec& s, double omega = 1.0) {
  DrumGeometry g;
  g.gravity = -9.81 * s.up;
  g.omega = omega;
  g.radius = s.radius_drum;
  return g;
}

TEST(DrumObservables, TiltedSlabGivesItsAngleAndLayer) {
  const SlabSpec s;
  const Particles p = tilted_slab(s);
  const DrumObservables o = measure_drum(p, geometry(s));
  ASSERT_TRUE(o.surface_found);
  EXPECT_GE(o.surface_points, 10u);
  EXPECT_NEAR(o.angle_of_repose_deg, 30.0, 0.2);
  // The fitted line lies within a particle diameter of the plane, so the layer does too.
  EXPECT_NEAR(o.flowing_layer_thickness, s.layer, 2.0 * s.r);
  EXPECT_LT(o.surface_curvature, 0.005);
  EXPECT_EQ(o.airborne_fraction, 0.0);
  EXPECT_TRUE(o.up.isApprox(Vec3::UnitY()));
  EXPECT_TRUE(o.carry.isApprox(Vec3::UnitX()));
}

TEST(DrumObservables, SlabCentreOfMassMatchesTheCircularSegment) {
  // Oracle: centroid of the disc (radius rho = R - r) on the side n.x <= d of a line, with
  // n = (-sin t, cos t) the line's upward normal: -(2/3)(rho^2 - d^2)^(3/2) / area * n.
  const SlabSpec s;
  const Particles p = tilted_slab(s);
  const DrumObservables o = measure_drum(p, geometry(s));
  const double t = s.theta_deg * kPi / 180.0;
  const double rho = s.radius_drum - s.r;
  const double d = (s.c - s.r) * std::cos(t);
  const double cap = rho * rho * std::acos(d / rho) - d * std::sqrt(rho * rho - d * d);
  const double dist = -(2.0 / 3.0) * std::pow(rho * rho - d * d, 1.5) / (kPi * rho * rho - cap);
  const Vec3 expected = dist * Vec3(-std::sin(t), std::cos(t), 0.0);
  EXPECT_NEAR(o.centre_of_mass.x(), expected.x(), 1e-3);
  EXPECT_NEAR(o.centre_of_mass.y(), expected.y(), 1e-3);
  EXPECT_NEAR(o.centre_of_mass.z(), 0.5 * s.depth, 1e-12);  // 5 symmetric layers
  EXPECT_NEAR(o.com_offset, expected.norm() / s.radius_drum, 2.0 * s.r / s.radius_drum);
  // The segment's centroid lies on the chord's perpendicular through the axis: the angle of the
  // COM from straight down is the surface's (the lattice's staircase costs a fraction of a degree).
  EXPECT_NEAR(o.com_angle_deg, s.theta_deg, 0.5);
  SlabSpec flat = s;
  flat.theta_deg = -12.0;
  EXPECT_NEAR(measure_drum(tilted_slab(flat), geometry(flat)).com_angle_deg, -12.0, 0.5);
}

TEST(DrumObservables, CentreOfMassAndEnergyOfTwoParticles) {
  Particles p;
  p.add(Vec3(0.0, -0.1, 0.01), 0.01, 1000.0);
  p.add(Vec3(0.1, -0.1, 0.03), 0.02, 1000.0);  // 8 times the mass
  p.velocity[0] = Vec3(1.0, 0.0, 0.0);
  p.omega[1] = Vec3(0.0, 0.0, 2.0);
  DrumGeometry g;
  g.radius = 0.3;
  const DrumObservables o = measure_drum(p, g);
  EXPECT_NEAR(o.centre_of_mass.x(), 0.1 * 8.0 / 9.0, 1e-12);
  EXPECT_NEAR(o.centre_of_mass.y(), -0.1, 1e-12);
  EXPECT_NEAR(o.centre_of_mass.z(), (0.01 + 8.0 * 0.03) / 9.0, 1e-12);
  const double m0 = 1000.0 * 4.0 / 3.0 * kPi * 1e-6;
  EXPECT_NEAR(o.mean_kinetic_energy, 0.25 * m0, 1e-12);
  EXPECT_NEAR(o.mean_rotational_energy, 0.5 * 0.5 * 0.4 * 8.0 * m0 * 4e-4 * 4.0, 1e-12);
  EXPECT_EQ(o.airborne_fraction, 1.0);  // neither touches anything
}

TEST(DrumObservables, FollowTheGravityAndTurningDirection) {
  // Gravity along -x: up = +x and, turning counter-clockwise, carry = z x (-up) = -y.
  SlabSpec s;
  s.up = Vec3::UnitX();
  s.carry = -Vec3::UnitY();
  const DrumObservables o = measure_drum(tilted_slab(s), geometry(s));
  EXPECT_TRUE(o.carry.isApprox(s.carry));
  EXPECT_NEAR(o.angle_of_repose_deg, 30.0, 0.5);
  EXPECT_NEAR(o.flowing_layer_thickness, s.layer, 2.0 * s.r);
  // The same bed in a drum turning the other way rises against the carry direction.
  const DrumObservables back = measure_drum(tilted_slab(s), geometry(s, -1.0));
  EXPECT_TRUE(back.carry.isApprox(-s.carry));
  EXPECT_NEAR(back.angle_of_repose_deg, -30.0, 0.5);
}

TEST(DrumObservables, SolidBodyRotationHasNoFlowingLayer) {
  SlabSpec s;
  s.theta_deg = 0.0;
  Particles p = tilted_slab(s);
  const double omega = 1.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.velocity[i] = omega * Vec3::UnitZ().cross(p.position[i]);
  }
  const DrumObservables o = measure_drum(p, geometry(s, omega));
  EXPECT_NEAR(o.angle_of_repose_deg, 0.0, 0.5);
  EXPECT_EQ(o.flowing_layer_thickness, 0.0);
  EXPECT_NEAR(o.mean_kinetic_energy, o.solid_body_energy, 1e-12 * o.solid_body_energy);
}

TEST(DrumObservables, ParticlesInFlightDoNotMoveTheSurface) {
  const SlabSpec s;
  Particles p = tilted_slab(s);
  const std::size_t bed = p.size();
  for (int k = 0; k < 4; ++k) p.add(Vec3(-0.02 + 0.03 * k, 0.1, 0.003), s.r, 2500.0);
  const DrumObservables o = measure_drum(p, geometry(s));
  EXPECT_NEAR(o.airborne_fraction, 4.0 / static_cast<double>(bed + 4), 1e-15);
  EXPECT_NEAR(o.angle_of_repose_deg, 30.0, 0.5);
}

TEST(DrumObservables, RejectsBadInput) {
  Particles p;
  p.add(Vec3(0.0, -0.1, 0.01), 0.01, 1000.0);
  DrumGeometry g;
  g.radius = 0.0;
  EXPECT_THROW(measure_drum(p, g), InputError);
  g.radius = 0.3;
  g.gravity = Vec3(0.0, 0.0, -9.81);  // along the axis: no cross-section direction
  EXPECT_THROW(measure_drum(p, g), InputError);
  g.gravity = Vec3(0.0, -9.81, 0.0);
  ObservableOptions bad;
  bad.end_exclusion = 0.6;
  EXPECT_THROW(measure_drum(p, g, bad), InputError);
  p.velocity[0].x() = NAN;
  EXPECT_THROW(measure_drum(p, g), InputError);
}

TEST(FlowRegime, MeasuredSlabIsRollingAndRigidBedIsSlumping) {
  const SlabSpec s;
  const std::vector<DrumObservables> flowing(3, measure_drum(tilted_slab(s), geometry(s)));
  EXPECT_EQ(classify_regime(flowing).regime, FlowRegime::rolling);
  Particles rigid = tilted_slab(s);
  for (std::size_t i = 0; i < rigid.size(); ++i) {
    rigid.velocity[i] = Vec3::UnitZ().cross(rigid.position[i]);
  }
  const std::vector<DrumObservables> still(3, measure_drum(rigid, geometry(s)));
  EXPECT_EQ(classify_regime(still).regime, FlowRegime::slumping);
  // A rigid rotation with the drum has no relative speed; the slab's flow has.
  EXPECT_LT(still[0].relative_speed, 1e-12);
  EXPECT_NEAR(still[0].wall_speed, s.radius_drum, 1e-15);
  EXPECT_GT(flowing[0].relative_speed, 0.05);
  // The profile holds every column bin in order; the fit uses its central part.
  const auto& profile = flowing[0].surface_profile;
  ASSERT_GT(profile.size(), flowing[0].surface_points);
  for (std::size_t k = 1; k < profile.size(); ++k) EXPECT_LT(profile[k - 1].h, profile[k].h);
  const auto fit = fit_surface_profile(profile, 0.2);
  ASSERT_TRUE(fit.has_value());
  EXPECT_DOUBLE_EQ(fit->angle_deg, flowing[0].angle_of_repose_deg);
}

// A planetary pot turning with its arm (k = 0): the field turns at the wall's rate, so nothing
// drives the bed; it sits against the far wall and turns with it: resting, not slumping.
TEST(FlowRegime, AWallThatTurnsWithTheFieldLeavesTheBedResting) {
  const SlabSpec s;
  Particles rigid = tilted_slab(s);
  for (std::size_t i = 0; i < rigid.size(); ++i) {
    rigid.velocity[i] = 2.0 * Vec3::UnitZ().cross(rigid.position[i]);
  }
  DrumGeometry g = geometry(s, 2.0);
  g.field_omega = 2.0;
  const std::vector<DrumObservables> window(3, measure_drum(rigid, g));
  EXPECT_EQ(window[0].wall_speed, 0.0);
  EXPECT_LT(window[0].relative_speed, 1e-12);
  EXPECT_DOUBLE_EQ(window[0].field, 9.81);
  EXPECT_EQ(window[0].radius, s.radius_drum);
  const RegimeEvidence e = classify_regime(window);
  EXPECT_EQ(e.regime, FlowRegime::resting);
  EXPECT_NE(regime_reason(e).find("not driven"), std::string::npos);
  // Driven at 1e-3 sqrt(g R) against the field it is no longer at rest (a slumping solid body).
  g.field_omega = 2.0 - 1.01e-3 * std::sqrt(9.81 / s.radius_drum);
  const std::vector<DrumObservables> driven(3, measure_drum(rigid, g));
  EXPECT_EQ(classify_regime(driven).regime, FlowRegime::slumping);
  // The carry direction follows the wall against the field: a pot turning slower than its arm
  // lifts the bed on the other side, so the same slab reads the opposite angle.
  g.field_omega = 3.0;
  const DrumObservables behind = measure_drum(tilted_slab(s), g);
  EXPECT_NEAR(behind.angle_of_repose_deg,
              -measure_drum(tilted_slab(s), geometry(s)).angle_of_repose_deg, 1e-9);
}

// Samples read back from a table carry no surface profile: the rules then take the samples' own
// curvature (their median), and say so.
TEST(FlowRegime, SamplesWithoutProfilesUseTheirOwnCurvature) {
  const SlabSpec s;
  std::vector<DrumObservables> window(3, measure_drum(tilted_slab(s), geometry(s)));
  const RegimeEvidence with = classify_regime(window);
  EXPECT_FALSE(with.sample_curvature);
  window[0].surface_curvature = 0.5;  // one noisy sample does not move the median
  for (auto& o : window) o.surface_profile.clear();
  const RegimeEvidence without = classify_regime(window);
  EXPECT_TRUE(without.sample_curvature);
  EXPECT_EQ(without.curvature, window[1].surface_curvature);
  EXPECT_EQ(without.regime, FlowRegime::rolling);
  EXPECT_NE(regime_reason(without).find("samples' curvature"), std::string::npos);
}

}  // namespace
}  // namespace drumlab
