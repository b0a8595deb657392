// libFuzzer harness: an STL file's bytes (binary or ASCII) read and built into a mesh with
// patches and the closedness check. Bad input must be an InputError; an accepted mesh has only
// finite vertices and unit normals.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "engine/mesh/stl_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const drumlab::TriangleMesh m =
        drumlab::make_mesh(drumlab::parse_stl(bytes, "fuzz.stl"), 0.17, "fuzz.stl");
    (void)drumlab::is_closed(m);
    for (const auto& v : m.vertices) {
      if (!v.allFinite()) std::abort();
    }
    for (const auto& n : m.normals) {
      if (!(std::abs(n.norm() - 1.0) < 1e-9)) std::abort();
    }
  } catch (const drumlab::InputError&) {
  }
  return 0;
}
