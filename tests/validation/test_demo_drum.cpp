// The demo drum itself (scenes/drum_demo.toml, 18,825 particles) for a fraction of a revolution,
// and a smaller drum run with every search method: the physics must not depend on the method.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_validation.hpp"
#include "engine/search/verlet_list.hpp"
#include "engine/simulation.hpp"
#include "engine/threads.hpp"

namespace drumlab {
namespace {

TEST(DemoDrum, FractionOfARevolutionKeepsEveryParticleInside) {
  SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/drum_demo.toml");
  Particles particles = random_fill(scene);
  const std::size_t n = particles.size();
  ASSERT_EQ(n, 18825u);
  auto mean_y = [](const Particles& p) {
    double y = 0.0;
    for (const Vec3& x : p.position) y += x.y();
    return y / static_cast<double>(p.size());
  };
  const double y0 = mean_y(particles);
  Simulation sim(scene, std::move(particles));
  sim.set_drum_omega(0.0);
  sim.advance(400);  // settling starts: particles fall and collide
  sim.set_drum_omega(scene.drum.omega);
  const double angle0 = sim.drum_angle();
  sim.advance(300);  // ~0.006 revolution of the turning drum
  const Diagnostics d = sim.diagnostics();
  EXPECT_EQ(sim.particles().size(), n);
  EXPECT_EQ(d.outside_drum, 0u);
  EXPECT_EQ(d.non_finite, 0u);
  EXPECT_LT(mean_y(sim.particles()), y0);  // it falls under gravity (-y)
  EXPECT_LT(d.max_overlap_ratio, 0.5);
  EXPECT_GT(d.contacts, n / 10);  // the falling bed has begun to form contacts
  EXPECT_GT(d.wall_contacts, 0u);
  EXPECT_NEAR(sim.drum_angle() - angle0, 300 * sim.dt() * scene.drum.omega, 1e-9);
  // Stable ids survive: still a permutation of 0..n-1.
  std::vector<Index> ids = sim.particles().id;
  std::sort(ids.begin(), ids.end());
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(ids[i], i);
}

// Runs `steps` steps with every search method from the same start; the positions must agree to
// the bit. Returns the first method's run's live bridges.
std::size_t expect_same_for_every_method(SceneConfig scene, std::uint64_t steps) {
  const Particles start = random_fill(scene);
  std::vector<Vec3> reference;
  std::size_t bridges = 0;
  for (const std::string& method : search_method_names()) {
    scene.search_method = method;
    Simulation sim(scene, start);
    sim.advance(steps);
    if (reference.empty()) {
      reference = sim.particles().position;
      EXPECT_GT(sim.diagnostics().contacts, 0u);
      bridges = sim.liquid().bridge_count;
      continue;
    }
    EXPECT_EQ(sim.particles().position, reference) << method;
  }
  return bridges;
}

TEST(SearchMethodsInADrum, TrajectoriesAreIdenticalForEveryMethod) {
  // Contacts are processed in (i, j) order whatever method found them, so the same contact set
  // gives bit-identical trajectories.
  expect_same_for_every_method(load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml"),
                               1500);
}

TEST(SearchMethodsInADrum, SwitchingMethodMidRunChangesNothing) {
  SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml");
  const Particles start = random_fill(scene);
  scene.search_method = "m5";
  Simulation a(scene, start);
  a.advance(1200);
  Simulation b(scene, start);
  b.advance(400);
  b.set_search_method("m2");
  b.advance(400);
  b.set_search_method("m3");
  b.advance(400);
  EXPECT_EQ(b.search().name(), "m3");
  EXPECT_EQ(a.particles().position, b.particles().position);
  EXPECT_EQ(a.particles().velocity, b.particles().velocity);
}

// A Verlet list patched for the particles that moved in the drum's frame (verlet_list.hpp) lists
// more pairs than one rebuilt, never fewer: the same contacts in the same order as a grid's.
TEST(SearchMethodsInADrum, APatchedVerletListChangesNoBit) {
  SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/drum_demo.toml");
  scene.fill.count = 6000;
  scene.fill.volume_fraction = 0.55;
  scene.performance.sort_every = 50;
  const Particles start = random_fill(scene);
  scene.search_method = "m2";
  Simulation grid(scene, start);
  grid.advance(2500);
  scene.search_method = "verlet:mlgrid";
  // One thread and three (uneven shares of the patch's scan and merge).
  const int saved = max_threads();
  for (const int threads : {1, 3}) {
    set_thread_count(threads);
    Simulation listed(scene, start);
    listed.advance(2500);
    const auto* verlet = dynamic_cast<const VerletListSearch*>(&listed.search());
    ASSERT_NE(verlet, nullptr);
    EXPECT_GT(verlet->patches(), 0u) << verlet->report();
    EXPECT_EQ(listed.particles().position, grid.particles().position) << threads << " threads";
    EXPECT_EQ(listed.particles().omega, grid.particles().omega) << threads << " threads";
  }
  set_thread_count(saved);
}

// The teaching drum with MercuryDPM's law parts (issue 33): the linear law set by a collision time
// (3 ms for two 10 mm spheres: ~25 steps), the rolling spring, liquid migration with equal films
// (film_radius), the proportional draw and the rupture into the other bridges. They must keep the
// invariants of the laws before them.
SceneConfig mercury_parts_scene() {
  SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml");
  scene.contact.normal = NormalLaw::linear_viscoelastic;
  scene.contact.collision_time = 3e-3;
  scene.contact.reference_radius = 0.01;
  scene.contact.rolling = RollingLaw::spring;
  scene.material.rolling_friction = scene.wall.rolling_friction = 0.5;
  LiquidConfig& l = scene.liquid;
  l.enabled = true;
  l.surface_tension = l.wall_surface_tension = 0.072;
  l.migration = true;
  l.liquid_content = 0.01;
  l.max_bridge_volume = 1e-8;
  l.film_radius = 0.01;
  l.proportional_draw = true;
  l.rupture_to_bridges = 1.0;
  validate(scene, "mercury parts");
  return scene;
}

TEST(SearchMethodsInADrum, MercuryLawPartsAreIdenticalForEveryMethod) {
  EXPECT_GT(expect_same_for_every_method(mercury_parts_scene(), 1500), 0u);
}

TEST(SearchMethodsInADrum, WetSizeDistributionsAreIdenticalForEveryMethod) {
  // The same wet drum with two polydisperse classes: a normal (sigma = 0.2 r, so r_max / r_min =
  // 4: several mlgrid levels, per-size stencils of every reach) and a table. Every method must
  // find the same contacts and bridges, so the runs agree to the bit.
  SceneConfig scene = mercury_parts_scene();
  ParticleClass normal{"normal", 0.005, 0.7};
  normal.distribution = SizeKind::normal;
  normal.radius_sigma = 0.001;
  ParticleClass table{"table", 0.0, 0.3};
  table.distribution = SizeKind::table;
  table.radii = {0.008, 0.010};
  table.shares = {2.0, 1.0};
  scene.classes = {normal, table};
  validate(scene, "wet size distributions");
  EXPECT_GT(expect_same_for_every_method(scene, 1500), 0u);
}

}  // namespace
}  // namespace drumlab

#ifdef _OPENMP
#include <omp.h>

namespace drumlab {
namespace {

// Runs `steps` steps with 1, 2 and 3 threads from the same start; the positions must agree to
// the bit.
// Returns the 1-thread run's overlapping contacts whose partner lies in another block of rows of
// the pair loop.
std::size_t expect_same_for_any_thread_count(const SceneConfig& scene, std::uint64_t steps) {
  const Particles start = random_fill(scene);
  std::vector<Vec3> reference;
  std::size_t cross_block = 0;
  const int saved = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    Simulation sim(scene, start);
    sim.advance(steps);
    if (reference.empty()) {
      reference = sim.particles().position;
      std::vector<ContactForce> contacts;
      sim.contact_forces(contacts);
      const std::size_t rows = scene.performance.pair_block_rows;
      for (const ContactForce& c : contacts) cross_block += c.i / rows != c.j / rows;
    } else {
      EXPECT_EQ(sim.particles().position, reference) << threads << " threads";
    }
  }
  omp_set_num_threads(saved);
  return cross_block;
}

TEST(Threads, ResultsAreIdenticalForOneAndTwoThreads) {
  // Pair forces are summed per particle in a fixed order, so the thread count changes nothing.
  SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml");
  scene.search_method = "verlet:m2";
  expect_same_for_any_thread_count(scene, 1500);
}

TEST(Threads, MercuryLawPartsAreIdenticalForAnyThreadCount) {
  SceneConfig scene = mercury_parts_scene();
  scene.search_method = "verlet:m2";
  expect_same_for_any_thread_count(scene, 1500);
}

TEST(Threads, ResultsAreIdenticalWithContactsAcrossRowBlocks) {
  // 6000 particles: 12 blocks of 512 rows, so many contacts join two blocks (their partner's
  // share goes through the cross-block buffers) and the blocks are shared out between threads.
  SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/drum_demo.toml");
  scene.fill.count = 6000;
  scene.fill.volume_fraction = 0.55;  // dense: contacts from the first steps
  scene.search_method = "verlet:mlgrid";
  scene.performance.sort_every = 50;
  scene.performance.pair_block_rows = 512;
  EXPECT_GT(expect_same_for_any_thread_count(scene, 1000), 200u);
}

}  // namespace
}  // namespace drumlab
#endif
