// The seam for laws that act beyond contact (issue 13 §1), with the pendular liquid bridge
// (issue 13 §2) as the law part that has a range: per-contact state in ContactList (carried over,
// renumbered, saved), registered per-particle arrays (re-ordered, saved), the search margin derived
// from the composed law (every method lists the same pairs up to the range), a bridge that
// survives separation within the rupture distance and is dropped beyond it, and bit-identical
// restarts of a wet drum with re-ordering. The force against Willett's closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "engine/contact/contact_history.hpp"
#include "engine/contact/liquid_bridge.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/scene/scene_features.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/spatial_order.hpp"
#include "engine/threads.hpp"
#include "tests/same_bits.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

// ---------------------------------------------------------------- per-contact state

TEST(ContactState, FollowsUpdateRenumberAndAssign) {
  ContactList c;
  c.set_state_size(2);
  const std::vector<IndexPair> first = {{0, 1}, {0, 2}, {1, 3}};
  c.update(first, 4);
  ASSERT_EQ(c.state().size(), 6u);
  for (double v : c.state()) EXPECT_EQ(v, 0.0);  // new pairs start at zero
  // Contact (0, 2) is k = 1, (1, 3) is k = 2.
  c.state()[2] = 7.0;
  c.state()[3] = 8.0;
  c.state()[4] = 9.0;
  c.history()[1] = Vec3(1.0, 2.0, 3.0);
  // (0, 2) stays, (1, 3) leaves, (2, 3) comes.
  const std::vector<IndexPair> second = {{2, 3}, {0, 2}, {0, 1}};
  c.update(second, 4);
  ASSERT_NE(c.find_state(0, 2), nullptr);
  EXPECT_EQ(c.find_state(0, 2)[0], 7.0);
  EXPECT_EQ(c.find_state(0, 2)[1], 8.0);
  EXPECT_EQ(c.find_state(2, 3)[0], 0.0);
  EXPECT_EQ(c.find_state(1, 3), nullptr);
  // The pair back again: its state was dropped with it.
  c.update(first, 4);
  EXPECT_EQ(c.find_state(1, 3)[0], 0.0);
  EXPECT_EQ(c.find_state(0, 2)[0], 7.0);

  // Re-ordering that flips (0, 2): the history is negated, the scalars are not.
  const std::vector<Index> new_index = {3, 1, 2, 0};
  c.renumber(new_index);
  ASSERT_NE(c.find_state(2, 3), nullptr);  // was (0, 2)
  EXPECT_EQ(c.find_state(2, 3)[0], 7.0);
  EXPECT_EQ(c.find_state(2, 3)[1], 8.0);
  EXPECT_EQ(*c.find(2, 3), Vec3(-1.0, -2.0, -3.0));

  // assign() checks the state's length against the partners.
  const std::vector<std::size_t> rows(c.row_start().begin(), c.row_start().end());
  const std::vector<Index> col(c.col().begin(), c.col().end());
  const std::vector<Vec3> hist(c.history().begin(), c.history().end());
  const std::vector<double> state(c.state().begin(), c.state().end());
  ContactList d;
  d.set_state_size(2);
  d.assign(rows, col, hist, state);
  EXPECT_EQ(d.find_state(2, 3)[1], 8.0);
  EXPECT_THROW(d.assign(rows, col, hist, std::span<const double>(state).first(3)), InputError);
  EXPECT_THROW(d.assign(rows, col, hist), InputError);
}

TEST(ContactState, DryListKeepsNoState) {
  ContactList c;
  const std::vector<IndexPair> pairs = {{0, 1}};
  c.update(pairs, 2);
  EXPECT_EQ(c.state_size(), 0u);
  EXPECT_TRUE(c.state().empty());
  EXPECT_EQ(c.find_state(0, 1), nullptr);
}

// ---------------------------------------------------------------- per-particle arrays

TEST(ParticleArrays, RegisteredOnceAndCarriedByReorderAndCheckpoint) {
  Particles p;
  for (int k = 0; k < 5; ++k) p.add(Vec3(0.01 * k, 0.0, 0.0), 0.001 * (k + 1), 1000.0);
  std::vector<double>& film = p.add_array("film_volume", 0.5);
  ASSERT_EQ(film.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) film[i] = 10.0 + static_cast<double>(i);
  p.add(Vec3(0.1, 0.0, 0.0), 0.002, 1000.0);
  EXPECT_EQ(p.find_array("film_volume")->back(), 0.5);
  EXPECT_THROW(p.add_array("film_volume"), InputError);
  EXPECT_THROW(p.add_array("radius"), InputError);
  EXPECT_THROW(p.add_array(""), InputError);
  EXPECT_EQ(p.find_array("none"), nullptr);

  std::vector<std::string> names;
  p.for_each_array([&](std::string_view name, const auto& a) {
    names.emplace_back(name);
    EXPECT_EQ(a.size(), p.size()) << name;
  });
  EXPECT_EQ(names.size(), 12u);
  EXPECT_EQ(names.back(), "film_volume");

  // Re-ordering moves the extra array with the ids.
  ReorderBuffers b;
  const std::vector<Index> order = {5, 3, 1, 0, 2, 4};
  p.reorder(order, b);
  const std::vector<double>& moved = *p.find_array("film_volume");
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Index id = p.id[k];
    EXPECT_EQ(moved[k], id == 5 ? 0.5 : 10.0 + id) << k;
  }
}

// ---------------------------------------------------------------- the bridge's force

TEST(LiquidBridge, ForceFollowsWillettsClosedForm) {
  const double gamma = 0.072, theta = 20.0 * std::numbers::pi / 180.0, v = 1e-12;
  const BridgeLiquid bridge{gamma, theta};
  EXPECT_DOUBLE_EQ(bridge.rupture_distance(v), (1.0 + 0.5 * theta) * std::cbrt(v));
  const double s_rup = bridge.rupture_distance(v);
  for (const auto& [r1, r2] :
       {std::pair{1e-3, 1e-3}, std::pair{1e-3, 3e-3}, std::pair{5e-4, 4e-3}}) {
    const double r = 2.0 * r1 * r2 / (r1 + r2);
    EXPECT_DOUBLE_EQ(LiquidBridge::pair_radius(r1, r2), r);
    const double f0 = 2.0 * std::numbers::pi * r * gamma * std::cos(theta);
    EXPECT_DOUBLE_EQ(bridge.force(-1e-6, r, v), f0);
    EXPECT_DOUBLE_EQ(bridge.force(0.0, r, v), f0);
    for (const double frac : {0.01, 0.1, 0.5, 0.9, 1.0}) {
      const double s = frac * s_rup;
      const double st = s * std::sqrt(r / v);
      const double expected = f0 / (1.0 + (1.05 + 2.5 * st) * st);
      EXPECT_NEAR(bridge.force(s, r, v), expected, 1e-14 * f0) << r1 << " " << r2 << " " << frac;
      EXPECT_GT(bridge.force(s, r, v), 0.0);
      EXPECT_LT(bridge.force(s, r, v), f0);
    }
  }
  EXPECT_DOUBLE_EQ(LiquidBridge::wall_radius(1e-3), 2e-3);
}

// ---------------------------------------------------------------- in a simulation

std::string wet_scene_text(const std::string& extra = "") {
  std::string text = output_scene_text();
  // A bridge volume giving s_rup = 1e-3 m: a quarter of the small radius, twice the Verlet skin.
  text += "[liquid]\nsurface_tension = 0.072\ncontact_angle_deg = 0\nbridge_volume = 1e-9\n";
  text += extra;
  return text;
}

SceneConfig wet_scene(const std::string& method = "m5", const std::string& extra = "") {
  SceneConfig s = parse_scene(wet_scene_text(extra), "wet-test");
  s.search_method = method;
  return s;
}

TEST(BeyondContact, DryLawHasNoRangeAndNoState) {
  const ContactModel dry(output_scene());
  EXPECT_EQ(dry.max_pair_range(), 0.0);
  EXPECT_EQ(dry.pair_state_size(), 0u);
  EXPECT_EQ(dry.part<LiquidBridge>(), nullptr);
  const ContactModel wet(wet_scene());
  EXPECT_NEAR(wet.max_pair_range(), 1e-3, 1e-15);
  EXPECT_EQ(wet.pair_range(0, 1), wet.max_pair_range());
  EXPECT_EQ(wet.pair_state_size(), LiquidBridge::kStateSize);
  // The dry drum's state carries nothing new.
  const auto sim = settled_simulation(output_scene(), 20);
  EXPECT_EQ(sim->state().contact_state_size, 0u);
  EXPECT_TRUE(sim->state().contact_state.empty());
}

// Every method lists every pair up to the range (the brute-force oracle with the law's margin),
// and the wet run is bit-identical across methods.
TEST(BeyondContact, EveryMethodListsThePairsUpToTheRange) {
  const SceneConfig base = wet_scene();
  const Particles start = random_fill(base);
  const double range = ContactModel(base).max_pair_range();
  std::vector<Vec3> reference_position;
  for (const std::string& method : search_method_names()) {
    SCOPED_TRACE(method);
    SceneConfig scene = base;
    scene.search_method = method;
    Simulation sim(scene, start);
    sim.advance(300);
    const SimulationState s = sim.state();
    // The oracle on the current positions, with the derived margin.
    SearchInput in{s.particles.position, s.particles.radius, range, std::nullopt, std::nullopt};
    std::vector<IndexPair> expected;
    make_search("brute")->find_pairs(in, expected);
    std::sort(expected.begin(), expected.end());
    ASSERT_GT(expected.size(), 0u);
    // The listed pairs within the range (a Verlet list also holds its skin).
    std::vector<IndexPair> listed;
    std::size_t bridges = 0, bridges_apart = 0;
    for (std::size_t i = 0; i + 1 < s.contact_row_start.size(); ++i) {
      for (std::size_t k = s.contact_row_start[i]; k < s.contact_row_start[i + 1]; ++k) {
        const Index j = s.contact_col[k];
        const double gap = (s.particles.position[i] - s.particles.position[j]).norm() -
                           s.particles.radius[i] - s.particles.radius[j];
        if (gap <= range + kTouchTolerance) listed.push_back({static_cast<Index>(i), j});
        if (s.contact_state[k * s.contact_state_size] > 0.0) {
          ++bridges;
          bridges_apart += gap > 0.0;
          EXPECT_LE(gap, range) << "a bridge beyond the rupture distance";
        }
      }
    }
    EXPECT_EQ(listed, expected);
    EXPECT_GT(bridges, 3u);
    if (method == "m5") {
      EXPECT_GT(bridges_apart, 0u) << "no bridge outlived its contact";
    }
    if (reference_position.empty()) {
      reference_position = s.particles.position;
    } else {
      EXPECT_TRUE(same_bits(reference_position, s.particles.position));
    }
  }
}

// Two spheres pushed apart from contact: the bridge forms, holds them while the gap is within
// s_rup (the pair stays listed, its state lives), and is dropped beyond it.
TEST(BeyondContact, BridgeSurvivesSeparationWithinTheRangeAndIsDroppedBeyond) {
  for (const std::string method : {"brute", "m5", "verlet:m5"}) {
    SCOPED_TRACE(method);
    SceneConfig scene = wet_scene(method);
    scene.gravity = Vec3::Zero();
    scene.drum.omega = 0.0;
    const double r = 0.004;
    Particles p;
    p.add(Vec3(-r + 1e-6, 0.0, 0.025), r, 2500.0);
    p.add(Vec3(r - 1e-6, 0.0, 0.025), r, 2500.0);
    // Fast enough to break the bridge (its work up to s_rup is about 6e-7 J, the relative kinetic
    // energy 7e-6 J).
    p.velocity[0] = Vec3(-0.1, 0.0, 0.0);
    p.velocity[1] = Vec3(0.1, 0.0, 0.0);
    Simulation sim(scene, std::move(p));
    const double s_rup = ContactModel(scene).max_pair_range();
    bool seen_apart = false, seen_dropped = false;
    double speed_before = 0.0, last_age = -1.0;
    std::vector<Bond> bonds;
    for (int k = 0; k < 4000 && !seen_dropped; ++k) {
      const Particles& q = sim.particles();
      const double speed = (q.velocity[1] - q.velocity[0]).x();
      sim.step();
      const Particles& now = sim.particles();
      const double gap = (now.position[1] - now.position[0]).norm() - 2.0 * r;
      const SimulationState s = sim.state();
      const bool listed = !s.contact_col.empty();
      const double bridge = listed ? s.contact_state[0] : 0.0;
      if (gap > 0.0 && gap <= s_rup) {
        ASSERT_TRUE(listed) << "pair not listed at gap " << gap;
        EXPECT_GT(bridge, 0.0) << "bridge lost at gap " << gap;
        const double pull = BridgeLiquid{0.072, 0.0}.force(gap, r, 1e-9);
        EXPECT_GT(pull, 0.0);
        // The bond graph reports the bridge: its volume, its force (R = 2 r r / 2r = r), an age
        // that grows by one time step per step.
        sim.bonds(bonds);
        ASSERT_EQ(bonds.size(), 1u);
        EXPECT_EQ(bonds[0].volume, 1e-9);
        EXPECT_NEAR(bonds[0].force, pull, 1e-12 * pull);
        if (last_age >= 0.0) {
          EXPECT_NEAR(bonds[0].age, last_age + sim.dt(), 1e-9 * sim.dt());
        }
        last_age = bonds[0].age;
        // Attraction: the spheres' separation speed falls while the bridge holds.
        if (seen_apart) {
          EXPECT_LT((now.velocity[1] - now.velocity[0]).x(), speed);
        }
        seen_apart = true;
      }
      if (gap > s_rup) {
        EXPECT_EQ(bridge, 0.0) << "bridge beyond the rupture distance";
        sim.bonds(bonds);
        EXPECT_TRUE(bonds.empty());
        seen_dropped = true;
        speed_before = (now.velocity[1] - now.velocity[0]).x();
      }
    }
    EXPECT_TRUE(seen_apart);
    ASSERT_TRUE(seen_dropped) << "the spheres never separated beyond s_rup";
    // Beyond the rupture no force: the speed stays.
    sim.advance(10);
    const Particles& q = sim.particles();
    EXPECT_NEAR((q.velocity[1] - q.velocity[0]).x(), speed_before, 1e-12);
    EXPECT_TRUE(sim.state().contact_col.empty() || sim.state().contact_state[0] == 0.0);
  }
}

// A wet drum with re-ordering every 20 steps: restart from a checkpoint after N steps equals the
// uninterrupted 2N bit for bit, the bridges included; forgetting them changes the trajectory.
TEST(BeyondContact, WetRestartWithReorderingIsBitIdentical) {
  TempDir dir("beyond-contact-restart");
  const SceneConfig scene = wet_scene("m5", "[performance]\nsort_every = 20\n");
  ASSERT_EQ(scene.performance.sort_every, 20u);
  constexpr std::uint64_t kN = 200;
  const auto straight = settled_simulation(scene, 2 * kN);
  const auto first = settled_simulation(scene, kN);
  const SimulationState half = first->state();
  ASSERT_EQ(half.contact_state_size, LiquidBridge::kStateSize);
  ASSERT_GT(std::count_if(half.contact_state.begin(), half.contact_state.end(),
                          [](double v) { return v > 0.0; }),
            3);
  write_checkpoint(dir.path() / "half.h5", half, scene.name);
  const Checkpoint c = read_checkpoint(dir.path() / "half.h5");
  EXPECT_EQ(c.state.contact_state_size, LiquidBridge::kStateSize);
  EXPECT_TRUE(same_bits(c.state.contact_state, half.contact_state));
  Simulation continued(scene, c.state);
  continued.advance(kN);
  const SimulationState a = straight->state(), b = continued.state();
  EXPECT_TRUE(same_bits(a.particles.position, b.particles.position));
  EXPECT_TRUE(same_bits(a.particles.velocity, b.particles.velocity));
  EXPECT_EQ(a.particles.id, b.particles.id);
  EXPECT_EQ(a.contact_col, b.contact_col);
  EXPECT_TRUE(same_bits(a.contact_state, b.contact_state));

  SimulationState forgetful = half;
  std::fill(forgetful.contact_state.begin(), forgetful.contact_state.end(), 0.0);
  Simulation amnesiac(scene, std::move(forgetful));
  amnesiac.advance(kN);
  EXPECT_FALSE(same_bits(a.particles.position, amnesiac.particles().position));

  // A dry state does not restart a wet scene (and the reverse).
  EXPECT_THROW(Simulation(scene, settled_simulation(output_scene(), 5)->state()), InputError);
  EXPECT_THROW(Simulation(output_scene(), half), InputError);
}

// The bridges' pass sums in the same order for any thread count (the contact forces already do).
TEST(BeyondContact, WetRunIsBitIdenticalForAnyThreadCount) {
  const SceneConfig scene = wet_scene("m5");
  const Particles start = random_fill(scene);
  const int saved = max_threads();
  std::vector<Vec3> reference;
  for (const int threads : {1, 2, 3}) {
    set_thread_count(threads);
    Simulation sim(scene, start);
    sim.advance(200);
    if (reference.empty()) {
      reference = sim.particles().position;
    } else {
      EXPECT_TRUE(same_bits(reference, sim.particles().position)) << threads << " threads";
    }
  }
  set_thread_count(saved);
}

// The same with liquid migration and wall bridges on more rows than one block of the cohesive
// pass (granulation_small: 300 particles, blocks of kCohesionBlockRows), so the blocks run on
// different threads; and a grid method lists other pairs than the Verlet list: the same bits.
TEST(BeyondContact, MigratingRunIsBitIdenticalForAnyThreadCountAndMethod) {
  SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/granulation_small.toml");
  ASSERT_GT(scene.fill.count, kCohesionBlockRows);
  const Particles start = random_fill(scene);
  const int saved = max_threads();
  std::vector<Vec3> position;
  std::vector<double> film;
  for (const auto& [threads, method] : {std::pair{1, "verlet:m2"}, {2, "verlet:m2"}, {2, "m5"}}) {
    set_thread_count(threads);
    scene.search_method = method;
    Simulation sim(scene, start);
    sim.advance(1500);
    ASSERT_GT(sim.liquid().bridge_count, 50u);
    ASSERT_GT(sim.liquid().wall_bridge_count, 0u);
    const std::vector<double>& f = *sim.particles().find_array(kLiquidFilmArray);
    if (position.empty()) {
      position = sim.particles().position;
      film = f;
      continue;
    }
    EXPECT_TRUE(same_bits(position, sim.particles().position)) << threads << " " << method;
    EXPECT_TRUE(same_bits(film, f)) << threads << " " << method;
  }
  set_thread_count(saved);
}

TEST(BeyondContact, InfoSaysAWetSceneNeedsCohesion) {
  EXPECT_FALSE(scene_features(output_scene()).cohesion);
  const SceneFeatures wet = scene_features(wet_scene());
  EXPECT_TRUE(wet.cohesion);
  bool listed = false;
  for (const SceneFeature& f : wet.list) {
    if (f.term == "cohesion") {
      listed = true;
      EXPECT_EQ(f.use, FeatureUse::needed);
    }
  }
  EXPECT_TRUE(listed);
}

TEST(BeyondContact, CheckpointCarriesRegisteredParticleArrays) {
  TempDir dir("beyond-contact-arrays");
  auto sim = settled_simulation(output_scene(), 5);
  SimulationState s = sim->state();
  std::vector<double>& film = s.particles.add_array("film_volume", 0.25);
  for (std::size_t i = 0; i < film.size(); ++i) film[i] = 1e-12 * s.particles.id[i];
  write_checkpoint(dir.path() / "c.h5", s, "arrays");
  const Checkpoint c = read_checkpoint(dir.path() / "c.h5");
  const std::vector<double>* back = c.state.particles.find_array("film_volume");
  ASSERT_NE(back, nullptr);
  EXPECT_TRUE(same_bits(*back, film));
  EXPECT_EQ(c.state.particles.extra.front().initial, 0.25);
  // And a simulation re-orders it with the particles.
  SceneConfig scene = output_scene();
  Simulation restored(scene, c.state);
  restored.reorder_particles();
  const Particles& q = restored.particles();
  const std::vector<double>& moved = *q.find_array("film_volume");
  for (std::size_t k = 0; k < q.size(); ++k) EXPECT_EQ(moved[k], 1e-12 * q.id[k]) << k;
}

}  // namespace
}  // namespace drumlab::test
