#pragma once
// Particles from a CSV file with a header naming the columns x, y, z, r (metres; any order, extra
// columns ignored). Every problem is an InputError "FILE:LINE: reason".
#include <filesystem>
#include <string_view>
#include <vector>

#include "engine/types.hpp"

namespace drumlab {

struct ParticleTable {
  std::vector<Vec3> position;
  std::vector<double> radius;
};

ParticleTable read_particle_csv(const std::filesystem::path& file);
/// Same, from text (tests); `source` names it in messages.
ParticleTable parse_particle_csv(std::string_view text, std::string_view source);

}  // namespace drumlab
