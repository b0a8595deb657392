#include "app/cli/wall_mesh_files.hpp"

#include <system_error>

#include <fmt/format.h>

#include "engine/mesh/stl_file.hpp"
#include "engine/types.hpp"

namespace drumlab::cli {

std::string mesh_file_name(const std::string& key) {
  std::string name = key.starts_with("wall.") ? key.substr(5) : key;
  std::string out;
  for (const char c : name) {
    if (c == '[' || c == '.') {
      out += '_';
    } else if (c != ']') {
      out += c;
    }
  }
  return out + ".stl";
}

std::string mesh_summary(const WallMesh& w) {
  return fmt::format("{}: {} triangles, {} smooth patch{}, {}, {}", w.key, w.mesh.size(),
                     w.mesh.patches, w.mesh.patches == 1 ? "" : "es",
                     w.attach == MeshAttach::drum ? "turning with the drum" : "fixed in the lab",
                     is_closed(w.mesh) ? "closed" : "open");
}

std::vector<std::filesystem::path> write_mesh_files(const std::vector<WallMesh>& meshes,
                                                    const std::filesystem::path& dir) {
  std::error_code ec;
  const bool existed = std::filesystem::is_directory(dir, ec);
  if (!existed) std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw InputError(fmt::format("--write-mesh {}: cannot create the directory{}", dir.string(),
                                 ec ? " (" + ec.message() + ")" : std::string()));
  }
  std::vector<std::filesystem::path> written;
  try {
    for (const WallMesh& w : meshes) {
      const std::filesystem::path file = dir / mesh_file_name(w.key);
      write_stl(w.mesh, file);
      written.push_back(file);
    }
  } catch (...) {
    for (const auto& file : written) std::filesystem::remove(file, ec);
    if (!existed) std::filesystem::remove(dir, ec);  // only if empty
    throw;
  }
  return written;
}

}  // namespace drumlab::cli
