#pragma once
// STL files (binary and ASCII) read into triangle corners and written from a mesh. Every damage
// is one InputError naming the file and what is wrong: a missing or unreadable file, a binary
// file shorter or longer than its triangle count says, an ASCII file whose facets do not parse,
// a file without triangles. (Non-finite and degenerate triangles are make_mesh's to refuse.)
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/mesh/triangle_mesh.hpp"

namespace drumlab {

/// The triangles of an STL file, three corners each, in the file's order. Binary files are told
/// from ASCII ones by their size (84 + 50 n bytes for n triangles), as most readers do, since
/// binary headers may begin with "solid" too.
std::vector<std::array<Vec3, 3>> read_stl(const std::filesystem::path& file);
/// The same for a file's bytes; `name` names it in errors.
std::vector<std::array<Vec3, 3>> parse_stl(std::string_view bytes, const std::string& name);

/// Writes `mesh` as a binary STL (float coordinates), atomically (FILE.tmp, then renamed).
void write_stl(const TriangleMesh& mesh, const std::filesystem::path& file);

}  // namespace drumlab
