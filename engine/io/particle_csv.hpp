#pragma once
// Particles from a CSV file with a header naming the columns x, y, z, r (metres; any order, extra
// columns ignored) and optionally vx, vy, vz (m/s; all three or none). Values must be finite
// numbers, radii positive. Every problem is an InputError "FILE:LINE: reason".
#include <filesystem>
#include <string_view>
#include <vector>

#include "engine/types.hpp"

namespace drumlab {

struct ParticleTable {
  std::vector<Vec3> position;
  std::vector<double> radius;
  std::vector<Vec3> velocity;     ///< empty unless the file has the columns vx, vy, vz
  std::vector<std::size_t> line;  ///< 1-based line of each particle in the file (for messages)
};

ParticleTable read_particle_csv(const std::filesystem::path& file);
/// Same, from text (tests); `source` names it in messages.
ParticleTable parse_particle_csv(std::string_view text, std::string_view source);

}  // namespace drumlab
