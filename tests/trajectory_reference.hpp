#pragma once
// A stored reference of a trajectory (tests/data/*_reference.txt) and the fingerprint it holds:
// a 64-bit FNV-1a hash of the positions, velocities and angular velocities (and the liquid films,
// if the particles carry them) in id order, and a few particles' values in hexadecimal floating
// point. Used by the reference tests in tests/validation/ (bit-identical, no tolerance).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "engine/contact/cohesion_loops.hpp"
#include "engine/particles.hpp"

namespace drumlab::test {

inline void fnv1a(std::uint64_t& h, const void* data, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < n; ++k) {
    h ^= bytes[k];
    h *= 1099511628211ull;
  }
}

inline std::string hex(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%a", x);
  return buffer;
}

/// The state as lines "key value": the hash and `samples` particles (by id).
inline std::map<std::string, std::string> fingerprint(const Particles& p, std::size_t samples) {
  std::vector<std::size_t> slot(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) slot[p.id[i]] = i;
  const std::vector<double>* film = p.find_array(kLiquidFilmArray);
  std::uint64_t h = 1469598103934665603ull;
  for (const std::size_t i : slot) {
    fnv1a(h, p.position[i].data(), 3 * sizeof(double));
    fnv1a(h, p.velocity[i].data(), 3 * sizeof(double));
    fnv1a(h, p.omega[i].data(), 3 * sizeof(double));
    if (film != nullptr) fnv1a(h, &(*film)[i], sizeof(double));
  }
  std::map<std::string, std::string> out;
  out["hash"] = std::to_string(h);
  for (std::size_t k = 0; k < samples; ++k) {
    const std::size_t id = k * (p.size() / samples);
    const std::size_t i = slot[id];
    std::string value;
    for (const Vec3* v : {&p.position[i], &p.velocity[i], &p.omega[i]}) {
      for (int c = 0; c < 3; ++c) value += hex((*v)[c]) + " ";
    }
    if (film != nullptr) value += hex((*film)[i]) + " ";
    out["particle_" + std::to_string(id)] = value;
  }
  return out;
}

inline std::map<std::string, std::string> read_reference(const std::string& file) {
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

/// Writes `now` to `file` under the header line `what` and the commit named by
/// DRUMLAB_REFERENCE_COMMIT; false if the file cannot be written.
inline bool write_reference(const std::string& file, const std::string& what,
                            const std::map<std::string, std::string>& now) {
  std::ofstream out(file);
  const char* commit = std::getenv("DRUMLAB_REFERENCE_COMMIT");
  out << "# " << what << "\n# written by the commit after " << (commit ? commit : "(unknown)")
      << "\n";
  for (const auto& [key, value] : now) out << key << " " << value << "\n";
  return out.good();
}

/// The test's verdict on `now` against the reference in `file`: each stored key equal (no
/// tolerance). With DRUMLAB_WRITE_REFERENCE set, writes `now` there instead (header `what`) and
/// skips. Call it last in a test.
inline void expect_reference(const std::string& file, const std::string& what,
                             const std::map<std::string, std::string>& now) {
  if (std::getenv("DRUMLAB_WRITE_REFERENCE") != nullptr) {
    ASSERT_TRUE(write_reference(file, what, now)) << "cannot write " << file;
    GTEST_SKIP() << "reference written to " << file;
  }
  const auto expected = read_reference(file);
  ASSERT_FALSE(expected.empty()) << "no reference at " << file;
  for (const auto& [key, value] : expected) {
    ASSERT_TRUE(now.count(key)) << key;
    EXPECT_EQ(now.at(key), value) << key << " differs from the reference";
  }
}

}  // namespace drumlab::test
