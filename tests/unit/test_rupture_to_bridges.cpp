// MercuryDPM's rupture rule ([liquid] rupture_to_bridges, its distribution coefficient): a
// ruptured bridge's halves go to the particles' other bridges, against a hand-computed case; the
// liquid accounting of a run with it; the key's validation.
#include <gtest/gtest.h>

#include <vector>

#include "engine/contact/contact_model.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/scene/scene_validation.hpp"
#include "engine/simulation.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab {
namespace {

constexpr double kVmax = 1e-9;

SceneConfig scene_with(const std::string& tables) {
  SceneConfig s = parse_scene(test::output_scene_text() + tables, "rupture-test");
  s.search_method = "m5";
  return s;
}

std::string migration(double c) {
  return "[liquid]\nsurface_tension = 0.072\nliquid_content = 0.01\nmax_bridge_volume = 1e-9\n"
         "wall_bridges = false\nrupture_to_bridges = " +
         std::to_string(c) + "\n";
}

struct Case {
  Particles p;
  ContactList contacts;
  PairForceBuffers buffers;
};

// Particle 0 at the origin bridged with 1 (far beyond the rupture distance: its bridge of
// 0.4 V_max ruptures), with 2 (0.1 V_max) and with 3 (0.95 V_max), both touching 0; particle 1 has
// no other bridge. Films: 1e-10 each. One step of the pair forces with distribution coefficient c.
std::vector<double> rupture_once(double c, std::vector<double>& films) {
  const SceneConfig scene = scene_with(migration(c));
  const ContactModel model(scene);
  const double r = scene.classes.front().radius;
  Case k;
  Particles& p = k.p;
  p.add(Vec3::Zero(), r, scene.material.density);
  p.add(Vec3(2.0 * r + 0.01, 0.0, 0.0), r, scene.material.density);
  p.add(Vec3(-(2.0 * r - 1e-6), 0.0, 0.0), r, scene.material.density);
  p.add(Vec3(0.0, 2.0 * r - 1e-6, 0.0), r, scene.material.density);
  p.add_array(kLiquidFilmArray, 1e-10);
  k.contacts.set_state_size(model.pair_state_size());
  const std::vector<IndexPair> pairs = {{0, 1}, {0, 2}, {0, 3}};
  k.contacts.update(pairs, 4);
  const std::size_t off = model.cohesive_parts().offset<LiquidBridge>();
  const std::size_t stride = model.pair_state_size();
  const double volumes[] = {0.4 * kVmax, 0.1 * kVmax, 0.95 * kVmax};
  for (std::size_t q = 0; q < 3; ++q) k.contacts.state()[q * stride + off] = volumes[q];
  p.clear_forces();
  model.add_pair_forces(p, k.contacts, k.buffers, 0.0, 1e-5, 1e-5);
  films = *p.find_array(kLiquidFilmArray);
  std::vector<double> out;
  for (std::size_t q = 0; q < 3; ++q) out.push_back(k.contacts.state()[q * stride + off]);
  return out;
}

TEST(RuptureToBridges, HalvesGoToTheOtherBridgesToppedAtVmax) {
  std::vector<double> films;
  // c = 1 (MercuryDPM's default): particle 0's half 0.2 V_max in two shares of 0.1 V_max: bridge
  // (0, 2) grows to 0.2 V_max, (0, 3) to 1.05 V_max, topped at V_max, 0.05 V_max to film 0;
  // particle 1 has no other bridge: its half to its film.
  std::vector<double> v = rupture_once(1.0, films);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_NEAR(v[1], 0.2 * kVmax, 1e-24);
  EXPECT_EQ(v[2], kVmax);
  EXPECT_NEAR(films[0], 1e-10 + 0.05 * kVmax, 1e-24);
  EXPECT_NEAR(films[1], 1e-10 + 0.2 * kVmax, 1e-24);
  EXPECT_EQ(films[2], 1e-10);
  EXPECT_EQ(films[3], 1e-10);
  // c = 0.5: 0.1 V_max of the half to the film, 0.05 V_max to each bridge ((0, 3) reaches V_max).
  v = rupture_once(0.5, films);
  EXPECT_NEAR(v[1], 0.15 * kVmax, 1e-24);
  EXPECT_NEAR(v[2], kVmax, 1e-24);
  EXPECT_NEAR(films[0], 1e-10 + 0.1 * kVmax, 1e-24);
  EXPECT_NEAR(films[1], 1e-10 + 0.2 * kVmax, 1e-24);
  // c = 0: today's rule, each half to its film.
  v = rupture_once(0.0, films);
  EXPECT_EQ(v[1], 0.1 * kVmax);
  EXPECT_EQ(v[2], 0.95 * kVmax);
  EXPECT_NEAR(films[0], 1e-10 + 0.2 * kVmax, 1e-24);
  EXPECT_NEAR(films[1], 1e-10 + 0.2 * kVmax, 1e-24);
}

// A wet drum with c = 1: films + bridges hold the scene's liquid to 1e-12 relative at every
// frame (every 50 steps), and some bridges ruptured into others (the run differs from c = 0).
TEST(RuptureToBridges, LiquidIsConservedAtEveryFrame) {
  const SceneConfig scene = scene_with(migration(1.0));
  const Particles start = random_fill(scene);
  Simulation sim(scene, start);
  const double total = sim.liquid().total();
  ASSERT_GT(total, 0.0);
  for (int frame = 0; frame < 40; ++frame) {
    sim.advance(50);
    EXPECT_NEAR(sim.liquid().total(), total, 1e-12 * total) << frame;
  }
  EXPECT_GT(sim.liquid().bridge_count, 5u);
  SceneConfig films_only = scene;
  films_only.liquid.rupture_to_bridges = 0.0;
  Simulation other(films_only, start);
  other.advance(2000);
  EXPECT_NE(other.liquid().bridges, sim.liquid().bridges);
}

TEST(RuptureToBridges, KeyIsValidated) {
  SceneConfig s = scene_with(migration(1.0));
  s.liquid.rupture_to_bridges = 1.5;
  const auto problem = scene_problem(s);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->key, "liquid.rupture_to_bridges");
  EXPECT_THROW(scene_with("[liquid]\nsurface_tension = 0.072\nbridge_volume = 1e-9\n"
                          "rupture_to_bridges = 1\n"),
               InputError);
}

}  // namespace
}  // namespace drumlab
