// The read-only contact accessors used by the VTU/contacts output: coordination numbers count
// overlapping pairs only, and contact_forces() gives the engine's own pair force (checked exactly
// on an undamped, frictionless pair, where the force depends on positions alone) without changing
// the simulation.
#include <gtest/gtest.h>

#include "engine/simulation.hpp"

namespace drumlab {
namespace {

SceneConfig free_space_scene() {
  SceneConfig s;
  s.name = "contact-output";
  s.search_method = "brute";
  s.gravity = Vec3::Zero();
  s.classes = {ParticleClass{"grain", 0.01, 1.0}};
  s.material = Material{2500.0, 5e6, 0.3, 1.0, 0.0, 0.0};  // e = 1: no damping; no friction
  s.wall = s.material;
  s.drum = DrumConfig{1.0, 1.0, 0.0, 0.0, DrumEnds::caps, {}};
  return s;
}

TEST(ContactOutput, CoordinationAndPairForcesMatchTheEngine) {
  Particles p;
  p.add(Vec3(0.0, 0.0, 0.5), 0.01, 2500.0);
  p.add(Vec3(0.0195, 0.001, 0.5), 0.01, 2500.0);  // overlaps particle 0 by ~0.5 mm
  p.add(Vec3(0.0, 0.0201, 0.5), 0.01, 2500.0);    // 0.1 mm from particle 0: not touching
  p.add(Vec3(0.2, 0.0, 0.5), 0.01, 2500.0);       // alone
  Simulation sim(free_space_scene(), std::move(p));
  sim.step();

  std::vector<std::uint32_t> coordination;
  sim.coordination_numbers(coordination);
  EXPECT_EQ(coordination, (std::vector<std::uint32_t>{1, 1, 0, 0}));

  std::vector<ContactForce> contacts;
  const SimulationState before = sim.state();
  sim.contact_forces(contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].i, 0u);
  EXPECT_EQ(contacts[0].j, 1u);
  EXPECT_GT(contacts[0].force.norm(), 0.0);
  EXPECT_EQ(contacts[0].force, sim.particles().force[0]);
  EXPECT_EQ(-contacts[0].force, sim.particles().force[1]);
  // Read only: the state is unchanged.
  EXPECT_EQ(sim.state().contact_history, before.contact_history);
  EXPECT_EQ(sim.particles().force, before.particles.force);
}

}  // namespace
}  // namespace drumlab
