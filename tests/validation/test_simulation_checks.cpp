// Simulation set-up checks, stability checks, periodic ends and the bookkeeping around the step.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "physics_test_helpers.hpp"

namespace drumlab {
namespace {

Particles one_particle(const Vec3& x, double r = 0.01) {
  Particles p;
  p.add(x, r, 2500.0);
  return p;
}

TEST(SimulationSetup, DefaultTimeStepIsAFractionOfTheRayleighTime) {
  const SceneConfig s = test::make_scene(0.01);
  Simulation sim(s, one_particle(Vec3(0, 0, 0.5)));
  const double g = 5e6 / (2.0 * 1.3);
  const double t_r = M_PI * 0.01 * std::sqrt(2500.0 / g) / (0.1631 * 0.3 + 0.8766);
  EXPECT_NEAR(sim.rayleigh_time(), t_r, 1e-15);
  EXPECT_NEAR(rayleigh_time(0.01, s.material), t_r, 1e-15);
  EXPECT_NEAR(sim.dt(), 0.2 * t_r, 1e-15);
  SimulationOptions o;
  o.dt_factor_override = 0.1;
  EXPECT_NEAR(Simulation(s, one_particle(Vec3(0, 0, 0.5)), o).dt(), 0.1 * t_r, 1e-15);
}

TEST(SimulationSetup, DtAboveTheRayleighTimeNeedsTheUnsafeOption) {
  SceneConfig s = test::make_scene(0.01);
  s.source = "scenes/x.toml";
  s.time.dt = 1.0;
  try {
    Simulation sim(s, one_particle(Vec3(0, 0, 0.5)));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(
        msg.find("scenes/x.toml: time.dt = 1 s is above the stability limit of 0.5 Rayleigh times"),
        std::string::npos)
        << msg;
    EXPECT_NE(msg.find("--unsafe-dt"), std::string::npos) << msg;
  }
  SimulationOptions o;
  o.allow_unsafe_dt = true;
  EXPECT_NO_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.5)), o));
  // The limit is half the Rayleigh time: 0.6 t_R is refused, 0.5 t_R accepted.
  s.time.dt.reset();
  s.time.dt_factor = 0.6;
  EXPECT_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.5))), InputError);
  s.time.dt_factor = 0.5;
  EXPECT_NO_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.5))));
}

// A linear law's own stiffness bounds dt, not the Young's modulus: 0.2 undamped half-periods
// pi sqrt(m*/k) of two of the lightest particles (m* = m/2).
TEST(SimulationSetup, LinearLawsAreBoundedByTheirContactPeriod) {
  SceneConfig s = test::make_scene(0.01);
  s.source = "scenes/x.toml";
  s.contact.normal = NormalLaw::linear;
  s.contact.linear_stiffness = 1e4;
  const double m = 2500.0 * 4.0 / 3.0 * M_PI * 1e-6;
  const double period = M_PI * std::sqrt(0.5 * m / 1e4);  // 2.27e-3 s
  // Far above 0.5 Rayleigh times (1.2e-4 s for E = 5 MPa) and yet stable for this soft spring.
  s.time.dt = 0.19 * period;
  EXPECT_NO_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.5))));
  s.time.dt = 0.21 * period;
  try {
    Simulation sim(s, one_particle(Vec3(0, 0, 0.5)));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("scenes/x.toml: time.dt = "), std::string::npos) << msg;
    EXPECT_NE(msg.find("0.2 contact half-periods of the linear contact law"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("--unsafe-dt"), std::string::npos) << msg;
  }
  // The collision-time law: MercuryDPM's drum (t_c = 1.43e-3 s for two 2 mm spheres) at its
  // dt = 0.05 t_c with particles down to 0.7 of the mean radius.
  s.contact.normal = NormalLaw::linear_viscoelastic;
  s.contact.collision_time = 1.42857e-3;
  s.contact.reference_radius = 2e-3;
  s.material.density = 1500.0;
  s.material.restitution = 0.5;
  s.time.dt = 0.05 * 1.42857e-3;
  EXPECT_NO_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.5), 1.4e-3)));
  s.time.dt = 0.2 * 1.42857e-3;  // 0.35 half-periods of the lightest pair
  EXPECT_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.5), 1.4e-3)), InputError);
}

TEST(SimulationSetup, ParticlesOutsideTheDrumAreRejected) {
  const SceneConfig s = test::make_scene(0.01);  // D = 1, H = 1, caps
  EXPECT_THROW(Simulation(s, one_particle(Vec3(0.6, 0, 0.5))), InputError);
  EXPECT_THROW(Simulation(s, one_particle(Vec3(0, 0, 1.2))), InputError);
  EXPECT_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.002))), InputError);  // deep in the cap
  EXPECT_NO_THROW(Simulation(s, one_particle(Vec3(0, -0.49, 0.5))));
  SceneConfig bad = s;
  bad.search_method = "no-such-method";
  EXPECT_THROW(Simulation(bad, one_particle(Vec3(0, 0, 0.5))), InputError);
}

TEST(SimulationStability, RunawayOverlapIsReportedWithStepAndTime) {
  SceneConfig s = test::make_scene(0.01);
  Particles p;
  p.add(Vec3(0, 0, 0.5), 0.01, 2500.0);
  p.add(Vec3(0.008, 0, 0.5), 0.01, 2500.0);  // overlap 1.2 radii
  Simulation sim(s, std::move(p));
  EXPECT_GT(sim.diagnostics().max_overlap_ratio, 0.5);
  try {
    sim.advance(1);
    FAIL() << "expected UnstableError";
  } catch (const UnstableError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("step 1 "), std::string::npos) << msg;
    EXPECT_NE(msg.find("overlap"), std::string::npos) << msg;
  }
}

TEST(SimulationStability, UnsafeTimeStepBlowsUpIntoAnUnstableError) {
  SceneConfig s = test::make_scene(0.01);
  s.gravity = Vec3(0, -9.81, 0);
  s.drum = DrumConfig{0.1, 0.05, 0.0, 0.0, DrumEnds::caps, {}};
  s.time.dt = 50.0 * rayleigh_time(0.01, s.material);
  SimulationOptions o;
  o.allow_unsafe_dt = true;
  Simulation sim(s, one_particle(Vec3(0, -0.035, 0.025)), o);
  EXPECT_THROW(sim.advance(2000), UnstableError);
}

// Two particles meeting head on across the periodic end: they must collide through the boundary
// (linear law, e = 0.9: restitution within 1 %), positions stay in [0, H), and no cap acts.
TEST(PeriodicDrum, CollisionThroughThePeriodicEnd) {
  SceneConfig s = test::make_scene(0.01);
  s.drum = DrumConfig{1.0, 0.2, 0.0, 0.0, DrumEnds::periodic, {}};
  s.contact.normal = NormalLaw::linear;
  s.contact.linear_stiffness = 1e4;
  s.material.restitution = 0.9;
  s.time.dt = 2e-6;
  Particles p;
  p.add(Vec3(0, 0, 0.0105), 0.01, 2500.0);
  p.add(Vec3(0, 0, 0.2 - 0.0105), 0.01, 2500.0);
  p.velocity[0] = Vec3(0, 0, -0.5);
  p.velocity[1] = Vec3(0, 0, 0.5);
  Simulation sim(s, std::move(p));
  bool touched = false;
  for (int k = 0; k < 5000; ++k) {
    sim.step();
    touched = touched || sim.diagnostics().contacts > 0;
    for (const Vec3& x : sim.particles().position) {
      ASSERT_GE(x.z(), 0.0);
      ASSERT_LT(x.z(), 0.2);
    }
  }
  EXPECT_TRUE(touched);
  EXPECT_EQ(sim.diagnostics().wall_contacts, 0u);
  const double e = (sim.particles().velocity[0].z() - sim.particles().velocity[1].z()) / 1.0;
  EXPECT_NEAR(e, 0.9, 0.009);
}

TEST(PeriodicDrum, ParticleCrossingTheEndIsWrapped) {
  SceneConfig s = test::make_scene(0.01);
  s.drum = DrumConfig{1.0, 0.2, 0.0, 0.0, DrumEnds::periodic, {}};
  s.time.dt = 1e-4;
  Particles p = one_particle(Vec3(0, 0, 0.19));
  p.velocity[0] = Vec3(0, 0, 1.0);
  Simulation sim(s, std::move(p));
  sim.advance(200);  // travels 0.02 m
  EXPECT_NEAR(sim.particles().position[0].z(), 0.01, 1e-12);
  // Periodic ends need a depth of more than 4 largest radii.
  s.drum.depth = 0.03;
  EXPECT_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.01))), InputError);
  // A bridge reaches past contact: s_rup = V^(1/3) = 5 mm (theta = 0), so the depth must exceed
  // 2 (2 r + s_rup) = 0.05 m, not 4 r = 0.04 m.
  s.liquid.enabled = true;
  s.liquid.surface_tension = 0.072;
  s.liquid.wall_surface_tension = 0.072;
  s.liquid.bridge_volume = 1.25e-7;
  s.drum.depth = 0.049;
  try {
    Simulation sim(s, one_particle(Vec3(0, 0, 0.01)));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("would reach two images"), std::string::npos) << e.what();
  }
  s.drum.depth = 0.051;
  EXPECT_NO_THROW(Simulation(s, one_particle(Vec3(0, 0, 0.01))));
}

TEST(SimulationBookkeeping, SearchSwitchTimersAndCounters) {
  SceneConfig s = test::make_scene(0.01);
  s.gravity = Vec3(0, -9.81, 0);
  s.material.friction = 0.5;
  s.wall.friction = 0.5;
  s.drum = DrumConfig{0.2, 0.05, 1.0, 0.0, DrumEnds::caps, {}};
  Particles p;
  for (int k = 0; k < 5; ++k) p.add(Vec3(-0.04 + 0.02 * k, -0.075, 0.025), 0.0099, 2500.0);
  Simulation sim(s, std::move(p));
  sim.advance(100);
  EXPECT_EQ(sim.steps(), 100u);
  EXPECT_EQ(sim.search_totals().pairs_tested, 100u * 10u);  // brute force: N(N-1)/2 per step
  EXPECT_GT(sim.timers().total(), 0.0);
  EXPECT_NEAR(sim.drum_angle(), 100 * sim.dt() * 1.0, 1e-15);
  sim.set_search_method("brute");
  EXPECT_EQ(sim.search().name(), "brute");
  EXPECT_THROW(sim.set_search_method("nope"), InputError);
  EXPECT_EQ(sim.search().name(), "brute");
  sim.set_drum_omega(0.0);
  EXPECT_EQ(sim.drum_omega(), 0.0);
  sim.advance(2000);  // settle on the wall at rest
  const Diagnostics d = sim.diagnostics();
  EXPECT_EQ(d.non_finite, 0u);
  EXPECT_EQ(d.outside_drum, 0u);
  EXPECT_GT(d.wall_contacts, 0u);
  EXPECT_GT(d.kinetic_energy + d.rotational_energy, 0.0);
}

}  // namespace
}  // namespace drumlab
