// Pins the dry demo drum's trajectory to a stored reference (tests/data/dry_demo_reference.txt),
// so that a change which must leave dry scenes alone (a new law, a new per-contact state, a new
// search margin) proves it does: 1,000 steps of scenes/drum_demo.toml from its random fill with
// the drum turning, which exercises particle and wall contacts with friction, Verlet-list
// rebuilds and the re-ordering every 100 steps. Tolerance: none (bit-identical). The reference
// holds a 64-bit FNV-1a hash of the positions, velocities and angular velocities in id order and
// a few particles' values in hexadecimal floating point, with the commit that wrote it.
//
// Fused multiply-adds change the round-off, so the reference belongs to the AVX2 + FMA build
// (the default on a CPU that has them); elsewhere the test is skipped. To rewrite the reference
// after a change that must alter trajectories (say so in its commit, with the measured size of
// the change), run the test with DRUMLAB_WRITE_REFERENCE=1.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"
#include "tests/trajectory_reference.hpp"

namespace drumlab {
namespace {

constexpr std::uint64_t kSteps = 1000;
constexpr std::size_t kSampleCount = 8;

std::string reference_path() {
  return std::string(DRUMLAB_TEST_DATA_DIR) + "/dry_demo_reference.txt";
}

TEST(DryReference, DemoDrumTrajectoryIsBitIdenticalToTheStoredReference) {
#ifndef DRUMLAB_AVX2_BUILD
  GTEST_SKIP() << "the reference belongs to the AVX2 + FMA build (FMA changes the round-off)";
#endif
#ifdef DRUMLAB_SANITIZED
  GTEST_SKIP() << "the reference belongs to the Release build: the sanitizers' checks change "
                  "where GCC fuses multiply-adds (the round-off)";
#endif
  const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/drum_demo.toml");
  Simulation sim(scene, random_fill(scene));
  sim.advance(kSteps);
  test::expect_reference(
      reference_path(),
      "tests/validation/test_dry_reference.cpp: scenes/drum_demo.toml, random fill, " +
          std::to_string(kSteps) + " steps, drum turning",
      test::fingerprint(sim.particles(), kSampleCount));
}

}  // namespace
}  // namespace drumlab
