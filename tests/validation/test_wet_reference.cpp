// Pins the wet drum's trajectory to a stored reference (tests/data/wet_granulation_reference.txt),
// as test_dry_reference.cpp pins the dry one: 1,500 steps of scenes/granulation_small.toml from its
// random fill with the drum turning: liquid bridges form, age and rupture, the films give and take
// liquid (migration), and the wall bridges too. The fingerprint includes every film. A change to
// the cohesive passes that must not change the physics (a faster loop, a batch) proves it here;
// one that must alter wet trajectories says so in its commit with the measured size of the change
// and rewrites the reference (DRUMLAB_WRITE_REFERENCE=1). Tolerance: none (bit-identical); the
// AVX2 + FMA build only, as the dry reference.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"
#include "tests/trajectory_reference.hpp"

namespace drumlab {
namespace {

constexpr std::uint64_t kSteps = 1500;
constexpr std::size_t kSampleCount = 6;

std::string reference_path() {
  return std::string(DRUMLAB_TEST_DATA_DIR) + "/wet_granulation_reference.txt";
}

TEST(WetReference, GranulationDrumTrajectoryIsBitIdenticalToTheStoredReference) {
#ifndef DRUMLAB_AVX2_BUILD
  GTEST_SKIP() << "the reference belongs to the AVX2 + FMA build (FMA changes the round-off)";
#endif
#ifdef DRUMLAB_SANITIZED
  GTEST_SKIP() << "the reference belongs to the Release build: the sanitizers' checks change "
                  "where GCC fuses multiply-adds (the round-off)";
#endif
  const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/granulation_small.toml");
  Simulation sim(scene, random_fill(scene));
  sim.advance(kSteps);
  ASSERT_GT(sim.liquid().bridge_count, 50u);
  ASSERT_GT(sim.liquid().wall_bridge_count, 0u);
  test::expect_reference(
      reference_path(),
      "tests/validation/test_wet_reference.cpp: scenes/granulation_small.toml, random fill, " +
          std::to_string(kSteps) + " steps, drum turning",
      test::fingerprint(sim.particles(), kSampleCount));
}

}  // namespace
}  // namespace drumlab
