// A planetary drum ([drum.orbit], engine/drum_orbit.hpp): the keys and their one-line errors,
// the carrier's field in the engine against the closed form (a free particle moves on a straight
// line in the lab frame), the critical speed ratio of a ball carried by the wall, a restart that
// carries the carrier's angle bit for bit, and the regime map of `sweep` over the speed ratio.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

#include "engine/drum_orbit.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

/// A drum of diameter D with an orbit table `orbit` (its lines) and the drum's own rate line
/// `rate` (empty: none).
std::string scene_text(const std::string& orbit, const std::string& rate = "omega = 2.0\n",
                       const std::string& gravity = "[0.0, -9.81, 0.0]",
                       const std::string& diameter = "0.2") {
  return "gravity = " + gravity + "\n[drum]\ndiameter = " + diameter + "\ndepth = 0.05\n" + rate +
         (orbit.empty() ? std::string() : "[drum.orbit]\n" + orbit) +
         "[[particles]]\nradius = 0.004\nvolume_fraction = 1.0\n"
         "[material]\ndensity = 2500.0\nyoungs_modulus = 5e6\npoisson_ratio = 0.3\n"
         "restitution = 0.5\nfriction = 0.5\n[fill]\ncount = 100\nsettle_time = 0.01\n"
         "[time]\ndt_factor = 0.2\nduration = 0.01\n";
}

TEST(DrumOrbit, KeysAreReadAndBadOnesAreOneLineNamingTheKey) {
  const SceneConfig s = parse_scene(scene_text("radius = 0.3\nrpm = 60.0\n"), "p.toml");
  EXPECT_TRUE(s.drum.orbit.active());
  EXPECT_DOUBLE_EQ(s.drum.orbit.omega, 2.0 * std::numbers::pi);
  EXPECT_EQ(s.drum.omega, 2.0);  // the absolute rate, as given
  const SceneConfig k =
      parse_scene(scene_text("radius = 0.3\nomega = 10.0\nspeed_ratio = -2.5\n", ""), "p.toml");
  EXPECT_DOUBLE_EQ(k.drum.omega, -15.0);  // Omega (1 + k)
  EXPECT_DOUBLE_EQ(speed_ratio(k.drum), -2.5);
  EXPECT_FALSE(parse_scene(scene_text(""), "p.toml").drum.orbit.active());
  const struct {
    std::string text, expected;
  } bad[] = {
      {scene_text("radius = -0.3\nomega = 10.0\n"), "drum.orbit.radius: must be > 0"},
      {scene_text("radius = 0.3\nomega = 0.0\n"), "drum.orbit.omega: must be a finite, non-zero"},
      {scene_text("radius = 0.3\n"), "drum.orbit.omega"},
      {scene_text("omega = 10.0\n"), "drum.orbit.radius"},
      {scene_text("radius = 0.3\nomega = 1.0\nrpm = 10.0\n"), "drum.orbit.rpm: give either"},
      {scene_text("radius = 0.3\nomega = 1.0\nspeed_ratio = 1.0\n"), "drum.omega: give the drum's"},
      {scene_text("radius = 0.3\nomega = 1.0\narm = 1.0\n"), "drum.orbit.arm: unknown key"},
      {scene_text("radius = 0.3\nomega = 1.0\n", "omega = 2.0\ntilt_deg = 10.0\n"),
       "drum.orbit: only with an untilted drum"},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(b.expected);
    try {
      parse_scene(b.text, "bad.toml");
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad.toml: " + b.expected), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

// A particle that touches nothing feels gravity + Omega^2 c(t) in the translating frame, so in
// the lab frame (x + c) it moves uniformly: x(t) = x0 + c(0) - c(t) + (v0 + c'(0)) t with g = 0.
// Velocity Verlet's error for this smooth force is O((Omega dt)^2): over one revolution the
// position stays within 10 (Omega dt)^2 R_o of it and the lab velocity within 10 (Omega dt)^2
// Omega R_o (a missing or wrong field term would be off by R_o itself).
TEST(DrumOrbit, AFreeParticleMovesUniformlyInTheLabFrame) {
  const SceneConfig scene =
      parse_scene(scene_text("radius = 0.05\nomega = 10.0\nphase_deg = 30.0\n", "omega = 0.0\n",
                             "[0.0, 0.0, 0.0]", "1.0"),
                  "free.toml");
  Particles p;
  p.add(Vec3(0.0, 0.0, 0.025), 0.004, 2500.0);
  p.velocity[0] = Vec3(0.01, -0.02, 0.0);
  Simulation sim(scene, p);
  const Vec3 x0 = p.position[0], v0 = p.velocity[0];
  const Vec3 c0 = sim.carrier_offset(), w0 = sim.carrier_velocity();
  EXPECT_NEAR(c0.x(), 0.05 * std::cos(std::numbers::pi / 6.0), 1e-15);
  const double period = 2.0 * std::numbers::pi / 10.0;
  const double step2 = std::pow(10.0 * sim.dt(), 2);
  ASSERT_LT(step2, 1e-4);
  double worst = 0.0;
  while (sim.time() < period) {
    sim.advance(50);
    const double t = sim.time();
    const Vec3 expected = x0 + c0 - sim.carrier_offset() + (v0 + w0) * t;
    worst = std::max(worst, (sim.particles().position[0] - expected).norm());
    // The lab-frame velocity is constant.
    EXPECT_NEAR((sim.particles().velocity[0] + sim.carrier_velocity() - v0 - w0).norm(), 0.0,
                10.0 * step2 * 10.0 * 0.05);
  }
  std::printf(
      "free particle: worst distance from the lab-frame line %.3g m over one carrier turn "
      "(bound %.3g m)\n",
      worst, 10.0 * step2 * 0.05);
  EXPECT_LT(worst, 10.0 * step2 * 0.05);
  EXPECT_GT(worst, 0.0);
  // The carrier turned once: its angle is the phase plus Omega t.
  EXPECT_NEAR(sim.carrier_angle(), std::numbers::pi / 6.0 + 10.0 * sim.time(), 1e-9);
  const Diagnostics d = sim.diagnostics();
  EXPECT_NEAR(d.lab_kinetic_energy, 0.5 * sim.particles().mass[0] * (v0 + w0).squaredNorm(),
              1e-6 * d.lab_kinetic_energy);
}

TEST(DrumOrbit, CriticalSpeedRatioIsTheSquareRootOfTheRadii) {
  DrumConfig d;
  d.diameter = 0.1;
  d.orbit.radius = 0.2;
  d.orbit.omega = 10.0;
  // omega^2 rho = Omega^2 R_o at the critical ratio.
  const double rho = 0.045, k1 = critical_speed_ratio(d.orbit, rho);
  EXPECT_NEAR(k1 * k1 * 100.0 * rho, 100.0 * 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(carrier_field(d.orbit), 20.0);
  d.omega = 10.0 * 1.1 * critical_speed_ratio(d.orbit, 0.05 - 0.005);
  EXPECT_EQ(predicted_regime(d, 0.001, 0.005), PlanetaryRegime::held);
  d.omega = -10.0 * 1.1 * critical_speed_ratio(d.orbit, 0.045);  // |1 + k| counts, not its sign
  EXPECT_EQ(predicted_regime(d, 0.001, 0.005), PlanetaryRegime::held);
  d.omega = 10.0 * 0.9 * critical_speed_ratio(d.orbit, 0.049);
  EXPECT_EQ(predicted_regime(d, 0.001, 0.005), PlanetaryRegime::released);
  d.omega =
      10.0 * 0.5 * (critical_speed_ratio(d.orbit, 0.045) + critical_speed_ratio(d.orbit, 0.049));
  EXPECT_EQ(predicted_regime(d, 0.001, 0.005), PlanetaryRegime::partly_held);
}

// A ball carried by the wall (turning with it, no slip) as it passes the point nearest the central
// axis, in the carrier's field alone: above the critical ratio the wall holds it (it stays
// pressed on for the next 50 ms); below, it leaves the wall there. (Whether a lone ball is
// carried that far at all depends on its slipping and rolling, which the closed form leaves out,
// so the test starts it there.)
double largest_gap_of_a_carried_ball(double ratio_over_critical, double r) {
  const double big_r = 0.05, rho = big_r - r, orbit_r = 0.2, big_omega = 10.0;
  const double omega = big_omega * ratio_over_critical * std::sqrt(orbit_r / rho);
  std::string text =
      scene_text("radius = 0.2\nomega = 10.0\n", "omega = " + std::to_string(omega) + "\n",
                 "[0.0, 0.0, 0.0]", "0.1");
  text += "[wall]\nfriction = 1.0\n";
  SceneConfig scene = parse_scene(text, "ball.toml");
  scene.material.rolling_friction = 0.5;
  scene.wall.rolling_friction = 0.5;
  scene.wall.friction = 1.0;
  scene.material.friction = 1.0;
  Particles p;
  // At the point nearest the central axis (c along +x at t = 0), turning with the wall.
  p.add(Vec3(-rho, 0.0, 0.025), r, 2500.0);
  p.velocity[0] = Vec3(0.0, -omega * rho, 0.0);
  p.omega[0] = Vec3(0.0, 0.0, omega);
  Simulation sim(scene, p);
  double largest = 0.0;
  while (sim.time() < 0.05) {
    sim.advance(20);
    const Vec3& x = sim.particles().position[0];
    largest = std::max(largest, big_r - r - std::hypot(x.x(), x.y()));
  }
  return largest;
}

// Two sizes, r = 5 mm and 15 mm (critical |1 + k| = sqrt(R_o / (R - r)) = 2.13 and 2.39).
// Measured for r = 5 mm: the largest gap in 50 ms is 5.5, 1.65, 0.45 and 0.08 mm at 0.8, 0.9,
// 0.95 and 0.98 of the critical ratio, and the ball never leaves the wall at 1.02, 1.05, 1.1 and
// 1.2 of it; the test asks for the transition within 5 % for both sizes (the gaps it prints).
TEST(DrumOrbit, TheWallHoldsABallAboveTheCriticalRatioAndReleasesItBelow) {
  for (const double r : {0.005, 0.015}) {
    const double held = largest_gap_of_a_carried_ball(1.05, r);
    const double released = largest_gap_of_a_carried_ball(0.95, r);
    const double thrown = largest_gap_of_a_carried_ball(0.7, r);
    std::printf(
        "ball r = %g m: largest gap %.3g m at 1.05, %.3g m at 0.95, %.3g m at 0.7 of the "
        "critical ratio\n",
        r, held, released, thrown);
    EXPECT_EQ(held, 0.0) << r;        // held: never a gap
    EXPECT_GT(released, 1e-5) << r;   // released there (any gap: the wall let go)
    EXPECT_GT(thrown, 0.5 * r) << r;  // flies off the wall
  }
}

TEST(DrumOrbit, ARestartCarriesTheCarrierBitForBit) {
  const SceneConfig scene =
      parse_scene(scene_text("radius = 0.3\nomega = 6.0\n", "omega = 2.0\n"), "p.toml");
  Simulation whole(scene, random_fill(scene));
  whole.advance(200);
  Simulation restarted(scene, whole.state());
  EXPECT_EQ(restarted.carrier_angle(), whole.carrier_angle());
  whole.advance(200);
  restarted.advance(200);
  EXPECT_EQ(restarted.particles().position, whole.particles().position);
  EXPECT_EQ(restarted.particles().velocity, whole.particles().velocity);
  // A scene without an orbit refuses a state with a carrier.
  const SceneConfig plain = parse_scene(scene_text(""), "plain.toml");
  EXPECT_THROW(Simulation(plain, whole.state()), InputError);
}

TEST(DrumOrbit, OneRunOfStepsIsStepByStepBitForBit) {
  // advance(n) is n single steps, bit for bit: the carrier turns between a step's two half kicks
  // and the particles are re-ordered every 100 steps (sort_every) on the way. (A version that
  // made each closing half kick in the next step's first pass was held to this.)
  const SceneConfig scene =
      parse_scene(scene_text("radius = 0.3\nomega = 6.0\n", "omega = 2.0\n"), "p.toml");
  ASSERT_EQ(scene.performance.sort_every, 100u);
  Simulation run(scene, random_fill(scene));
  Simulation single(scene, run.state());
  run.advance(250);
  for (int k = 0; k < 250; ++k) single.step();
  EXPECT_EQ(single.steps(), run.steps());
  EXPECT_EQ(single.particles().position, run.particles().position);
  EXPECT_EQ(single.particles().velocity, run.particles().velocity);
  EXPECT_EQ(single.particles().omega, run.particles().omega);
  const auto& omega = run.particles().omega;  // the particles spin: the rotation is tested
  EXPECT_TRUE(std::any_of(omega.begin(), omega.end(), [](const Vec3& w) { return w.norm() > 0; }));
}

TEST(DrumOrbit, InfoPrintsTheFieldTheCriticalRatiosAndTheRegime) {
  TempDir dir("orbit-info");
  const auto file = dir.write("p.toml", scene_text("radius = 0.3\nomega = 10.0\nspeed_ratio = "
                                                   "-3.0\n",
                                                   ""));
  const auto r = run_cli("info " + file.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Omega^2 R_o = 30 m/s^2 = 3.06 g"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("speed ratio k = omega / Omega - 1 = -3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("critical |1 + k| = sqrt(R_o / (R - r))"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("predicted: "), std::string::npos) << r.output;
}

// R_o = 0: an arm of no length is the plain drum, bit for bit (the carrier adds exactly nothing,
// whatever its rate), and the speed ratio still sets the drum's rate Omega (1 + k).
TEST(DrumOrbit, AnArmOfNoLengthIsThePlainDrumBitForBit) {
  const SceneConfig orbit =
      parse_scene(scene_text("radius = 0.0\nomega = 16.0\nspeed_ratio = -1.5\n", ""), "zero.toml");
  const SceneConfig plain = parse_scene(scene_text("", "omega = -8.0\n"), "plain.toml");
  EXPECT_EQ(orbit.drum.omega, plain.drum.omega);
  Simulation a(orbit, random_fill(orbit));
  Simulation b(plain, random_fill(plain));
  a.advance(400);
  b.advance(400);
  EXPECT_EQ(a.particles().position, b.particles().position);
  EXPECT_EQ(a.particles().velocity, b.particles().velocity);
  EXPECT_EQ(a.particles().omega, b.particles().omega);
  EXPECT_EQ(a.carrier_offset(), Vec3::Zero());
  EXPECT_EQ(a.body_acceleration(), b.body_acceleration());
  EXPECT_EQ(a.diagnostics().lab_kinetic_energy, b.diagnostics().kinetic_energy);
}

// `sweep` over the mill's speed ratio classifies each pot (flow_regime.hpp) against the closed
// form: at k = 0 nothing drives the bed (the pot turns with its arm): resting; at |1 + k| = 4,
// far above the critical 1.70, the wall holds the balls as a ring: centrifuging; at |1 + k| = 1,
// below it, the balls leave the wall: not centrifuging. 0.2 s per pot (1.3 carrier turns).
TEST(DrumOrbit, SweepOverTheSpeedRatioMapsRestingFlowingAndHeldBeds) {
  TempDir dir("orbit-sweep");
  const auto r = run_cli("sweep " + std::string(DRUMLAB_SCENES_DIR) +
                         "/planetary_mill.toml --set drum.orbit.speed_ratio=-2,0,3 --set "
                         "time.duration=0.2 --jobs 2 --threads 1 --out " +
                         dir.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(dir.path() / "sweep.csv");
  std::string header, line;
  std::getline(in, header);
  ASSERT_EQ(header.substr(header.rfind(',') + 1), "regime");
  std::vector<std::string> regimes;
  while (std::getline(in, line)) regimes.push_back(line.substr(line.rfind(',') + 1));
  ASSERT_EQ(regimes.size(), 3u);
  EXPECT_NE(regimes[0], "centrifuging");
  EXPECT_NE(regimes[0], "resting");
  EXPECT_EQ(regimes[1], "resting");
  EXPECT_EQ(regimes[2], "centrifuging");
  if (r.output.find("chart ") != std::string::npos) {  // a build with the render library
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "sweep.png"));
  }
}

}  // namespace
}  // namespace drumlab::test
