// libFuzzer harness: a particle packing CSV (`[fill] kind = "file"`). Bad input must be an
// InputError; an accepted table has finite positions and velocities and positive radii, one
// line number per particle.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "engine/io/particle_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const drumlab::ParticleTable t = drumlab::parse_particle_csv(text, "fuzz.csv");
    if (t.radius.size() != t.position.size() || t.line.size() != t.position.size()) std::abort();
    for (std::size_t i = 0; i < t.position.size(); ++i) {
      if (!t.position[i].allFinite() || !(t.radius[i] > 0.0) || !std::isfinite(t.radius[i])) {
        std::abort();
      }
    }
    for (const auto& v : t.velocity) {
      if (!v.allFinite()) std::abort();
    }
  } catch (const drumlab::InputError&) {
  }
  return 0;
}
