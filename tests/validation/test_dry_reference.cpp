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
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"

namespace drumlab {
namespace {

constexpr std::uint64_t kSteps = 1000;
constexpr std::size_t kSampleCount = 8;

std::string reference_path() {
  return std::string(DRUMLAB_TEST_DATA_DIR) + "/dry_demo_reference.txt";
}

void fnv1a(std::uint64_t& h, const void* data, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < n; ++k) {
    h ^= bytes[k];
    h *= 1099511628211ull;
  }
}

std::string hex(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%a", x);
  return buffer;
}

/// The state as lines "key value": the hash and the sampled particles (by id).
std::map<std::string, std::string> fingerprint(const Particles& p) {
  std::vector<std::size_t> slot(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) slot[p.id[i]] = i;
  std::uint64_t h = 1469598103934665603ull;
  for (const std::size_t i : slot) {
    fnv1a(h, p.position[i].data(), 3 * sizeof(double));
    fnv1a(h, p.velocity[i].data(), 3 * sizeof(double));
    fnv1a(h, p.omega[i].data(), 3 * sizeof(double));
  }
  std::map<std::string, std::string> out;
  out["hash"] = std::to_string(h);
  for (std::size_t k = 0; k < kSampleCount; ++k) {
    const std::size_t id = k * (p.size() / kSampleCount);
    const std::size_t i = slot[id];
    std::string value;
    for (const Vec3* v : {&p.position[i], &p.velocity[i], &p.omega[i]}) {
      for (int c = 0; c < 3; ++c) value += hex((*v)[c]) + " ";
    }
    out["particle_" + std::to_string(id)] = value;
  }
  return out;
}

std::map<std::string, std::string> read_reference(const std::string& file) {
  std::map<std::string, std::string> out;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t space = line.find(' ');
    if (space == std::string::npos) continue;
    out[line.substr(0, space)] = line.substr(space + 1);
  }
  return out;
}

TEST(DryReference, DemoDrumTrajectoryIsBitIdenticalToTheStoredReference) {
#ifndef DRUMLAB_AVX2_BUILD
  GTEST_SKIP() << "the reference belongs to the AVX2 + FMA build (FMA changes the round-off)";
#endif
  const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/drum_demo.toml");
  Simulation sim(scene, random_fill(scene));
  sim.advance(kSteps);
  const auto now = fingerprint(sim.particles());
  if (std::getenv("DRUMLAB_WRITE_REFERENCE") != nullptr) {
    std::ofstream out(reference_path());
    out << "# tests/validation/test_dry_reference.cpp: scenes/drum_demo.toml, random fill, "
        << kSteps << " steps, drum turning\n# written by the commit after "
        << (std::getenv("DRUMLAB_REFERENCE_COMMIT") ? std::getenv("DRUMLAB_REFERENCE_COMMIT")
                                                    : "(unknown)")
        << "\n";
    for (const auto& [key, value] : now) out << key << " " << value << "\n";
    ASSERT_TRUE(out.good()) << "cannot write " << reference_path();
    GTEST_SKIP() << "reference written to " << reference_path();
  }
  const auto expected = read_reference(reference_path());
  ASSERT_FALSE(expected.empty()) << "no reference at " << reference_path();
  for (const auto& [key, value] : expected) {
    ASSERT_TRUE(now.count(key)) << key;
    EXPECT_EQ(now.at(key), value) << key << " differs from the reference";
  }
}

}  // namespace
}  // namespace drumlab
