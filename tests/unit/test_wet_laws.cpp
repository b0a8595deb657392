// The granulation laws of issue 13 §2 through the code path the simulation runs: the liquid
// bridge (pair and wall) against Willett's closed form and its rupture, seen with the law probe
// (engine/contact/law_probe.hpp); the viscous term against its formula; liquid migration (films
// give and take, total liquid conserved through re-ordering and restart, the same on every search
// method); wall bridges restarted bit for bit; LIGGGHTS' sjkr adhesion (a cohesive pair at rest
// stays bound, a dry one separates, the pull-off force of the probe against the stated formula).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "engine/analysis/agglomerates.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/contact/law_probe.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/scene/scene_features.hpp"
#include "engine/search/contact_search.hpp"
#include "tests/same_bits.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

constexpr double kGamma = 0.072;
constexpr double kPi = std::numbers::pi;

// The small drum (radii 4 and 8 mm) with a [liquid] table of `liquid` lines (and `extra` after).
SceneConfig scene_with(const std::string& tables, const std::string& method = "m5") {
  SceneConfig s = parse_scene(output_scene_text() + tables, "wet-laws-test");
  s.search_method = method;
  return s;
}

// Liquid migration: 1 % liquid, bridges up to 1e-9 m^3 (s_rup = 1 mm, a quarter of the small
// radius; the small particle's film holds 2.7e-9 m^3).
const std::string kMigration =
    "[liquid]\nsurface_tension = 0.072\ncontact_angle_deg = 10\nliquid_content = 0.01\n"
    "max_bridge_volume = 1e-9\n";

// ---------------------------------------------------------------- the bridge, probed

TEST(WetLaws, ProbedBridgeForceFollowsWillettAtEveryGapRadiusPairAndWall) {
  const SceneConfig scene = scene_with(kMigration);
  const double theta = 10.0 * kPi / 180.0;
  struct Case {
    std::uint8_t a, b;
    bool wall;
  };
  for (const Case c : {Case{0, 0, false}, Case{0, 1, false}, Case{1, 1, false}, Case{0, 0, true},
                       Case{1, 0, true}}) {
    LawProbeOptions o;
    o.class_a = c.a;
    o.class_b = c.b;
    o.wall = c.wall;
    const LawCurve curve = probe_law(scene, o);
    SCOPED_TRACE(curve.label);
    const double r1 = scene.classes[c.a].radius, r2 = scene.classes[c.b].radius;
    const double r = c.wall ? 2.0 * r1 : 2.0 * r1 * r2 / (r1 + r2);
    const double f0 = 2.0 * kPi * r * kGamma * std::cos(theta);
    // The films (1 % of each particle's volume) exceed V_max: every bridge holds V_max.
    const double v = 1e-9;
    const double s_rup = (1.0 + 0.5 * theta) * std::cbrt(v);
    std::size_t apart = 0;
    for (const LawSample& s : curve.samples) {
      if (!s.retreat) {
        // Never touched on the way in: no bridge, no force while apart.
        if (s.gap > 0.0) {
          EXPECT_EQ(s.normal_force, 0.0) << s.gap;
          EXPECT_EQ(s.bridge_volume, 0.0) << s.gap;
        }
        continue;
      }
      if (s.gap <= 0.0) continue;  // overlapping: Hertz + F0
      if (s.gap <= s_rup) {
        const double st = s.gap * std::sqrt(r / v);
        const double expected = f0 / (1.0 + (1.05 + 2.5 * st) * st);
        // Summed forces of one pair: round-off of a few operations.
        EXPECT_NEAR(s.normal_force, -expected, 1e-12 * f0) << s.gap;
        EXPECT_EQ(s.bridge_volume, v);
        ++apart;
      } else {
        EXPECT_EQ(s.normal_force, 0.0) << s.gap;  // ruptured: nothing beyond s_rup
        EXPECT_EQ(s.bridge_volume, 0.0);
      }
    }
    EXPECT_GT(apart, 50u);
    // Rupture: the last bridged sample lies just before s_rup, the first free one after it.
    EXPECT_NEAR(curve.predicted_rupture, s_rup, 1e-15);
    EXPECT_LE(curve.last_bridged_gap, s_rup);
    EXPECT_GT(curve.rupture_gap, s_rup);
    const std::size_t n = curve.samples.size() / 2;  // the retreat's first sample
    const double spacing = curve.samples[n + 1].gap - curve.samples[n].gap;
    EXPECT_LT(curve.rupture_gap - curve.last_bridged_gap, 1.001 * spacing);
  }
}

// While two bridged spheres overlap, the bridge's pull is F0 (s~ = 0) on top of the contact
// force: the wet probe's force minus the dry probe's at the same overlaps (the same scene without
// [liquid]; the spheres at rest, so the contact force depends on the overlap alone) is -F0, to the
// round-off of one sum. The pair loop adds it there (TouchingPull), not the cohesive pass.
TEST(WetLaws, OverlappingBridgedPairsAddF0ToTheContactForce) {
  const SceneConfig wet = scene_with(kMigration);
  SceneConfig dry = parse_scene(output_scene_text(), "wet-laws-test-dry");
  dry.search_method = "m5";
  const double theta = 10.0 * kPi / 180.0;
  for (const auto& [a, b] : {std::pair<std::uint8_t, std::uint8_t>{0, 0}, {0, 1}, {1, 1}}) {
    LawProbeOptions o;
    o.class_a = a;
    o.class_b = b;
    o.end_gap = 2e-3;  // the same positions in both probes (the dry law has no range)
    const LawCurve w = probe_law(wet, o);
    const LawCurve d = probe_law(dry, o);
    SCOPED_TRACE(w.label);
    ASSERT_EQ(w.samples.size(), d.samples.size());
    const double r1 = wet.classes[a].radius, r2 = wet.classes[b].radius;
    const double f0 = 2.0 * kPi * (2.0 * r1 * r2 / (r1 + r2)) * kGamma * std::cos(theta);
    std::size_t bridged = 0;
    for (std::size_t k = 0; k < w.samples.size(); ++k) {
      const LawSample& sw = w.samples[k];
      const LawSample& sd = d.samples[k];
      ASSERT_EQ(sw.gap, sd.gap);
      if (!(sw.gap < 0.0)) continue;
      ASSERT_GT(sd.normal_force, 0.0) << sw.gap;   // overlapping: repulsive when dry
      ASSERT_GT(sw.bridge_volume, 0.0) << sw.gap;  // formed at the first touch, full films
      EXPECT_NEAR(sw.normal_force - sd.normal_force, -f0, 1e-13 * (sd.normal_force + f0)) << sw.gap;
      ++bridged;
    }
    EXPECT_GT(bridged, 60u);  // every overlapping sample, approach and retreat
  }
}

TEST(WetLaws, RuptureIsSharpAtSrup) {
  const SceneConfig scene = scene_with(kMigration);
  const double s_rup = (1.0 + 0.5 * 10.0 * kPi / 180.0) * std::cbrt(1e-9);
  for (const bool wall : {false, true}) {
    LawProbeOptions o;
    o.wall = wall;
    o.end_gap = s_rup * (1.0 + 1e-9);
    o.steps = 2000;
    const LawCurve just_before = probe_law(scene, o);
    // The last sample (at s_rup (1 + 1e-9)) has no bridge, the one before (s_rup - spacing) has.
    const LawSample& last = just_before.samples.back();
    const LawSample& before = just_before.samples[just_before.samples.size() - 2];
    EXPECT_GT(last.gap, s_rup);
    EXPECT_EQ(last.normal_force, 0.0);
    EXPECT_LT(before.gap, s_rup);
    EXPECT_LT(before.normal_force, 0.0) << "no pull just before s_rup";
  }
}

// ---------------------------------------------------------------- viscous term

TEST(WetLaws, ViscousTermFollowsItsFormula) {
  const SceneConfig scene =
      scene_with(kMigration + "viscosity = 0.05\nmin_gap = 1e-5\nwall_bridges = false\n");
  const ContactModel model(scene);
  const double r1 = 0.004, r2 = 0.008, theta = 10.0 * kPi / 180.0;
  for (const double gap : {-1e-6, 5e-6, 2e-4, 6e-4}) {
    for (const double vn : {-0.02, 0.0, 0.03}) {
      Particles p;
      p.add(Vec3(r1 + r2 + gap, 0.0, 0.025), r1, 2500.0, 0);
      p.add(Vec3(0.0, 0.0, 0.025), r2, 2500.0, 1);
      p.add_array(kLiquidFilmArray, 1e-9);
      p.velocity[0] = Vec3(vn, 0.0, 0.0);  // v_n > 0: separating
      ContactList contacts;
      contacts.set_state_size(model.pair_state_size());
      // Touch first (the bridge forms at contact), then the gap under test.
      const Vec3 x0 = p.position[0];
      p.position[0] = Vec3(r1 + r2 - 1e-7, 0.0, 0.025);
      const std::vector<IndexPair> pair = {{0, 1}};
      PairForceBuffers buf;
      contacts.update(pair, 2);
      model.add_pair_forces(p, contacts, buf, 0.0, 1e-6, 1e-6);
      p.position[0] = x0;
      p.clear_forces();
      contacts.update(pair, 2);
      model.add_pair_forces(p, contacts, buf, 0.0, 1e-6, 1e-6);
      const double v = contacts.find_state(0, 1)[0];
      ASSERT_GT(v, 0.0);
      const double r = 2.0 * r1 * r2 / (r1 + r2), r_star = r1 * r2 / (r1 + r2);
      double capillary = 2.0 * kPi * r * kGamma * std::cos(theta);
      if (gap > 0.0) {
        const double st = gap * std::sqrt(r / v);
        capillary /= 1.0 + (1.05 + 2.5 * st) * st;
      }
      const double viscous = -6.0 * kPi * 0.05 * r_star * r_star * vn / std::max(gap, 1e-5);
      double expected = viscous - capillary;  // along +x (towards particle 0)
      if (gap < 0.0) {
        // Overlapping: the contact force adds; compare its difference to the dry part's share.
        continue;
      }
      EXPECT_NEAR(p.force[0].x(), expected, 1e-12 * std::abs(expected) + 1e-18) << gap << " " << vn;
    }
  }
}

TEST(WetLaws, TheViscousTermBoundsTheTimeStep) {
  // m*/c of the lightest pair (r = 4 mm: m* = m/2, R* = r/2) at min_gap, and at the wall
  // (m* = m, R* = r: half of it) when the scene has wall bridges.
  const double r = 0.004, eta = 2.0, gap = 1e-5;
  const double m = 2500.0 * 4.0 / 3.0 * kPi * r * r * r;
  const double pair = 0.5 * m * gap / (6.0 * kPi * eta * 0.25 * r * r);
  const std::string viscous = "viscosity = 2\nmin_gap = 1e-5\n";
  const SceneConfig no_wall = scene_with(kMigration + viscous + "wall_bridges = false\n");
  ASSERT_TRUE(viscous_relaxation_time(no_wall, r));
  EXPECT_NEAR(*viscous_relaxation_time(no_wall, r), pair, 1e-12 * pair);
  const SceneConfig wall = scene_with(kMigration + viscous);
  EXPECT_NEAR(*viscous_relaxation_time(wall, r), 0.5 * pair, 1e-12 * pair);
  const TimeStepLimit limit = time_step_limit(wall, ContactModel(wall), r);
  EXPECT_EQ(limit.factor, 1.0);
  EXPECT_NEAR(limit.seconds(), 0.5 * pair, 1e-12 * pair);
  EXPECT_NE(std::string(limit.unit).find("viscous"), std::string::npos);
  // The scene's dt (0.2 Rayleigh times, about 1e-4 s) is above it: refused with one line naming
  // the keys; a thinner liquid is not bound by it.
  try {
    Simulation sim(wall, random_fill(wall));
    FAIL() << "a dt above the viscous limit was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("time.dt"), std::string::npos) << what;
    EXPECT_NE(what.find("liquid.viscosity"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  const SceneConfig thin = scene_with(kMigration + "viscosity = 0.001\nmin_gap = 1e-5\n");
  EXPECT_EQ(time_step_limit(thin, ContactModel(thin), r).unit, std::string("Rayleigh times"));
  EXPECT_FALSE(viscous_relaxation_time(scene_with(kMigration), r));
}

// ---------------------------------------------------------------- migration in a drum

double total_liquid(const SceneConfig& scene) {
  double v = 0.0;
  const Particles fill = random_fill(scene);
  for (double r : fill.radius) v += scene.liquid.liquid_content * 4.0 / 3.0 * kPi * r * r * r;
  return v;
}

TEST(WetLaws, LiquidIsConservedThroughReorderingAndRestart) {
  TempDir dir("wet-laws-conservation");
  const SceneConfig scene = scene_with(kMigration + "[performance]\nsort_every = 20\n");
  const double total = total_liquid(scene);
  constexpr std::uint64_t kN = 300;
  auto first = settled_simulation(scene, kN);
  const LiquidTotals mid = first->liquid();
  EXPECT_GT(mid.bridge_count, 10u);
  EXPECT_GT(mid.wall_bridge_count, 3u);
  EXPECT_GT(mid.bridges, 0.0);
  EXPECT_NEAR(mid.total(), total, 1e-12 * total);
  write_checkpoint(dir.path() / "half.h5", first->state(), scene.name);
  const Checkpoint c = read_checkpoint(dir.path() / "half.h5");
  Simulation continued(scene, c.state);
  continued.advance(kN);
  const LiquidTotals end = continued.liquid();
  EXPECT_NEAR(end.total(), total, 1e-12 * total);
  EXPECT_NEAR(continued.diagnostics().liquid_volume, total, 1e-12 * total);
  EXPECT_EQ(continued.diagnostics().bridges, end.bridge_count);
  // The restart is bit-identical to the run that did not stop (pair and wall bridges, films).
  first->advance(kN);
  const SimulationState a = first->state(), b = continued.state();
  EXPECT_TRUE(same_bits(a.particles.position, b.particles.position));
  EXPECT_TRUE(same_bits(a.contact_state, b.contact_state));
  for (const char* name : {"liquid_film", "wall_bridge_volume_mantle", "wall_bridge_age_low_cap"}) {
    ASSERT_NE(a.particles.find_array(name), nullptr) << name;
    EXPECT_TRUE(same_bits(*a.particles.find_array(name), *b.particles.find_array(name))) << name;
  }
}

// The agglomerate rows' liquid columns (films, pair bridges, wall bridges) add up to the scene's
// liquid at every frame, to round-off, and so do the printed columns (12 digits each).
TEST(WetLaws, AgglomerateLiquidColumnsSumToTheLiquid) {
  const SceneConfig scene = scene_with(kMigration);
  const double total = total_liquid(scene);
  auto sim = settled_simulation(scene, 0);
  std::vector<Bond> bonds;
  for (int frame = 0; frame < 3; ++frame) {
    sim->advance(frame == 0 ? 300 : 100);
    const AgglomerateStats s = find_agglomerates(agglomerate_input(*sim, bonds), {}).stats;
    EXPECT_GT(s.wall_liquid, 0.0);
    EXPECT_GT(s.bridge_liquid, 0.0);
    EXPECT_NEAR(s.free_liquid + s.bridge_liquid + s.wall_liquid, total, 1e-12 * total);
    std::stringstream row(agglomerate_csv_row(s));
    std::vector<double> column;
    for (std::string cell; std::getline(row, cell, ',');) {
      column.push_back(cell == s.criterion ? 0.0 : std::stod(cell));
    }
    ASSERT_EQ(column.size(), 17u);
    EXPECT_NEAR(column[9] + column[10] + column[11], total, 1e-11 * total);
  }
}

TEST(WetLaws, EverySearchMethodMakesTheSameBridgesAndFilms) {
  const SceneConfig base = scene_with(kMigration);
  const Particles start = random_fill(base);
  std::vector<double> films;
  std::vector<Bond> reference, bonds;
  for (const std::string& method : search_method_names()) {
    SCOPED_TRACE(method);
    SceneConfig scene = base;
    scene.search_method = method;
    Simulation sim(scene, start);
    sim.advance(300);
    sim.bonds(bonds);
    const std::vector<double>& f = *sim.particles().find_array(kLiquidFilmArray);
    if (films.empty()) {
      films = f;
      reference = bonds;
      ASSERT_GT(reference.size(), 5u);
      continue;
    }
    EXPECT_TRUE(same_bits(films, f));
    ASSERT_EQ(bonds.size(), reference.size());
    for (std::size_t k = 0; k < bonds.size(); ++k) {
      EXPECT_EQ(bonds[k].i, reference[k].i);
      EXPECT_EQ(bonds[k].j, reference[k].j);
      EXPECT_EQ(bonds[k].volume, reference[k].volume);
    }
  }
}

TEST(WetLaws, NoFilmNoBridgeAndTheInitialSplit) {
  // No liquid at all: bridges never form, though the spheres touch.
  const SceneConfig dry_films = scene_with(
      "[liquid]\nsurface_tension = 0.072\nliquid_content = 0\nmax_bridge_volume = 1e-9\n");
  auto sim = settled_simulation(dry_films, 200);
  EXPECT_EQ(sim->liquid().bridge_count, 0u);
  EXPECT_EQ(sim->liquid().wall_bridge_count, 0u);
  EXPECT_GT(sim->diagnostics().contacts, 0u);
  // Half the liquid reserved for bridges at the start: the random fill has no contacts, so it
  // all goes to the films.
  const SceneConfig split = scene_with(kMigration + "film_share = 0.5\n");
  Simulation s(split, random_fill(split));
  EXPECT_NEAR(s.liquid().films, total_liquid(split), 1e-12 * total_liquid(split));
}

// surface_tension = 0 (MercuryDPM's Bo = 0): bridges form, draw from the films and rupture, but
// pull with no force, so the particles move bit for bit as in the same drum without liquid.
TEST(WetLaws, ZeroSurfaceTensionMigratesLiquidWithoutForce) {
  std::string tables = kMigration;
  tables.replace(tables.find("0.072"), 5, "0");
  const SceneConfig wet = scene_with(tables);
  const SceneConfig dry = scene_with("");
  auto a = settled_simulation(wet, 400);
  auto b = settled_simulation(dry, 400);
  EXPECT_GT(a->liquid().bridge_count, 10u);
  EXPECT_NEAR(a->liquid().total(), total_liquid(wet), 1e-12 * total_liquid(wet));
  EXPECT_TRUE(same_bits(a->particles().position, b->particles().position));
  EXPECT_TRUE(same_bits(a->particles().omega, b->particles().omega));
}

// MercuryDPM's drum (LiquidMigrationWilletInteraction::form, RotatingDrumWet.cpp): a bridge of
// V_max draws from the films in proportion to them; every particle gets the film of a sphere of
// film_radius. The draw against its closed form, then a run: equal films, liquid conserved.
TEST(WetLaws, ProportionalDrawAndFilmRadius) {
  LiquidBridge b;
  b.migration = true;
  b.max_volume = 1e-9;
  b.proportional_draw = true;
  double fi = 3e-9, fj = 1e-9;
  EXPECT_EQ(b.take_from_films(fi, fj), 1e-9);
  EXPECT_NEAR(fi, 3e-9 - 0.75e-9, 1e-24);
  EXPECT_NEAR(fj, 1e-9 - 0.25e-9, 1e-24);
  fi = 0.25e-9, fj = 0.5e-9;  // below V_max: all of both films, as the halves
  EXPECT_DOUBLE_EQ(b.take_from_films(fi, fj), 0.75e-9);
  EXPECT_EQ(fi + fj, 0.0);
  b.proportional_draw = false;  // the halves: 0.5e-9 from each
  fi = 3e-9, fj = 1e-9;
  b.take_from_films(fi, fj);
  EXPECT_NEAR(fi, 2.5e-9, 1e-24);
  EXPECT_NEAR(fj, 0.5e-9, 1e-24);

  const SceneConfig scene =
      scene_with(kMigration + "film_radius = 0.005\nbridge_draw = \"proportional\"\n");
  const Particles start = random_fill(scene);
  Simulation sim(scene, start);
  const double r = 0.005;
  const double film = scene.liquid.liquid_content * (4.0 / 3.0) * kPi * r * r * r;
  for (double f : *sim.particles().find_array(kLiquidFilmArray)) EXPECT_EQ(f, film);
  const double total = film * static_cast<double>(start.size());
  sim.advance(300);
  EXPECT_GT(sim.liquid().bridge_count, 5u);
  EXPECT_NEAR(sim.liquid().total(), total, 1e-12 * total);
}

// ---------------------------------------------------------------- sjkr adhesion

// Two spheres of radius r at rest, slightly overlapped, no gravity, no drum motion.
std::unique_ptr<Simulation> resting_pair(const SceneConfig& scene, double overlap) {
  const double r = 0.004;
  Particles p;
  p.add(Vec3(-r + 0.5 * overlap, 0.0, 0.025), r, 2500.0);
  p.add(Vec3(r - 0.5 * overlap, 0.0, 0.025), r, 2500.0);
  return std::make_unique<Simulation>(scene, std::move(p));
}

TEST(WetLaws, CohesivePairAtRestStaysBoundDryOneSeparates) {
  SceneConfig dry = scene_with("");
  dry.gravity = Vec3::Zero();
  dry.drum.omega = 0.0;
  SceneConfig sticky = scene_with("[cohesion]\nmodel = \"sjkr\"\nenergy_density = 5e4\n");
  sticky.gravity = Vec3::Zero();
  sticky.drum.omega = 0.0;
  const ContactModel model(sticky);
  const double r_star = 0.002;
  const double e_star = std::get<HertzNormal>(model.pair_normal()).e_star;
  const double delta_eq = model.part<SjkrCohesion>()->rest_overlap(e_star, r_star);
  ASSERT_GT(delta_eq, 1e-6);
  const double overlap = 0.2 * delta_eq;  // inside the attractive basin (delta < delta_eq)
  auto a = resting_pair(dry, overlap);
  auto b = resting_pair(sticky, overlap);
  const auto gap = [](const Simulation& s) {
    const Particles& p = s.particles();
    return (p.position[1] - p.position[0]).norm() - p.radius[0] - p.radius[1];
  };
  std::vector<Bond> bonds;
  a->advance(20000);
  b->advance(20000);
  EXPECT_GT(gap(*a), 0.0) << "the dry pair stayed together";
  EXPECT_LT(gap(*b), 0.0) << "the cohesive pair came apart";
  // Damped towards the rest overlap delta_eq (a^2 = 2 R* delta to first order: 1 %).
  EXPECT_NEAR(-gap(*b), delta_eq, 0.02 * delta_eq);
  b->bonds(bonds);
  ASSERT_EQ(bonds.size(), 1u);
  EXPECT_EQ(bonds[0].volume, 0.0);
  EXPECT_GT(bonds[0].force, 0.0);
  EXPECT_NEAR(bonds[0].age, 20000 * b->dt(), 1e-6 * 20000 * b->dt());
  a->bonds(bonds);
  EXPECT_TRUE(bonds.empty());
}

TEST(WetLaws, ProbedPullOffMatchesTheStatedFormula) {
  const SceneConfig sticky = scene_with("[cohesion]\nmodel = \"sjkr\"\nenergy_density = 5e4\n");
  const ContactModel model(sticky);
  const double e_star = std::get<HertzNormal>(model.pair_normal()).e_star;
  const double r_star = 0.002;
  const SjkrCohesion& c = *model.part<SjkrCohesion>();
  LawProbeOptions o;
  o.overlap = 1.5 * c.rest_overlap(e_star, r_star);
  o.steps = 4000;
  const LawCurve curve = probe_law(sticky, o);
  double most_tensile = 0.0;
  for (const LawSample& s : curve.samples) most_tensile = std::min(most_tensile, s.normal_force);
  // F_pull from a^2 ~ 2 R* delta; the exact lens area differs by O(delta / r) ~ 1e-3.
  EXPECT_NEAR(-most_tensile, c.pull_off_force(e_star, r_star),
              0.01 * c.pull_off_force(e_star, r_star));
}

// ---------------------------------------------------------------- bad parameters

TEST(WetLaws, BadWetParametersAreRefusedWithOneLine) {
  TempDir dir("wet-laws-bad");
  struct Case {
    const char* what;
    std::string tables;
    const char* key;
  };
  const std::string liquid = "[liquid]\nsurface_tension = 0.072\n";
  const std::vector<Case> cases = {
      {"negative tension", "[liquid]\nsurface_tension = -0.07\nbridge_volume = 1e-9\n",
       "liquid.surface_tension"},
      {"angle 90", liquid + "contact_angle_deg = 90\nbridge_volume = 1e-9\n",
       "liquid.contact_angle_deg"},
      {"negative content", liquid + "liquid_content = -0.01\nmax_bridge_volume = 1e-9\n",
       "liquid.liquid_content"},
      {"zero max volume", liquid + "liquid_content = 0.01\nmax_bridge_volume = 0\n",
       "liquid.max_bridge_volume"},
      {"split above 1",
       liquid + "liquid_content = 0.01\nmax_bridge_volume = 1e-9\nfilm_share = 2\n",
       "liquid.film_share"},
      {"both volumes", liquid + "liquid_content = 0.01\nbridge_volume = 1e-9\n",
       "liquid.bridge_volume"},
      {"film radius without migration", liquid + "bridge_volume = 1e-9\nfilm_radius = 0.002\n",
       "liquid.film_radius"},
      {"negative film radius",
       liquid + "liquid_content = 0.01\nmax_bridge_volume = 1e-9\nfilm_radius = -0.002\n",
       "liquid.film_radius"},
      {"unknown draw",
       liquid + "liquid_content = 0.01\nmax_bridge_volume = 1e-9\nbridge_draw = \"all\"\n",
       "liquid.bridge_draw"},
      {"viscosity without gap", liquid + "bridge_volume = 1e-9\nviscosity = 0.01\n",
       "liquid.min_gap"},
      {"wall angle", liquid + "bridge_volume = 1e-9\nwall_contact_angle_deg = 95\n",
       "liquid.wall_contact_angle_deg"},
      {"negative cohesion", "[cohesion]\nenergy_density = -5\n", "cohesion.energy_density"},
      {"unknown cohesion", "[cohesion]\nmodel = \"jkr\"\nenergy_density = 5\n", "cohesion.model"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const auto file = dir.write("bad.toml", output_scene_text() + c.tables);
    const CliResult r = run_cli("info " + file.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find(file.string()), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.key), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

}  // namespace
}  // namespace drumlab::test

namespace drumlab::test {
namespace {

// ---------------------------------------------------------------- the shipped wet scenes

TEST(WetScenes, GranulationScenesStateTheirBondNumberAndFormBridges) {
  for (const char* name : {"granulation.toml", "granulation_small.toml"}) {
    SCOPED_TRACE(name);
    const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/" + name);
    // The files' comments state Bo = 4.9 and Fr = 0.010.
    EXPECT_NEAR(bond_number(scene, 0), 4.9, 0.05);
    EXPECT_NEAR(scene.drum.omega * scene.drum.omega * 0.5 * scene.drum.diameter / 9.81, 0.010,
                0.0005);
  }
  const SceneConfig small = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/granulation_small.toml");
  Simulation sim(small, random_fill(small));
  const double total = sim.liquid().total();
  sim.advance(1500);
  const LiquidTotals t = sim.liquid();
  EXPECT_GT(t.bridge_count, sim.particles().size());  // more than one bridge per particle
  EXPECT_GT(t.wall_bridge_count, 10u);
  EXPECT_NEAR(t.total(), total, 1e-12 * total);
}

TEST(WetScenes, LawCommandWritesCsvAndRefusesBadClasses) {
  TempDir dir("wet-laws-cli");
  const std::string scene = std::string(DRUMLAB_SCENES_DIR) + "/granulation_small.toml";
  const CliResult ok = run_cli("law " + scene + " --wall granule --out " + dir.path().string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("rupture           between"), std::string::npos) << ok.output;
  std::ifstream csv(dir.path() / "law.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "gap_or_overlap_m,normal_force_N,bridge_volume_m3,branch");
  std::size_t rows = 0, retreat = 0;
  for (std::string line; std::getline(csv, line); ++rows) retreat += line.ends_with(",retreat");
  EXPECT_EQ(rows, 800u);
  EXPECT_EQ(retreat, 400u);
  const CliResult bad =
      run_cli("law " + scene + " --pair granule,pebble --out " + (dir.path() / "bad").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("no particle class 'pebble'"), std::string::npos) << bad.output;
  EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "bad" / "law.csv"));
}

}  // namespace
}  // namespace drumlab::test
