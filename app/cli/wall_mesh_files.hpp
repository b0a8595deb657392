#pragma once
// `drumlab info SCENE --write-mesh DIR`: the scene's triangle walls ([[wall.mesh]],
// [[wall.lifters]]) as binary STL files, as built (scaled, turned, moved; the drum at angle 0),
// so a user sees what the scene makes of its keys.
#include <filesystem>
#include <string>
#include <vector>

#include "engine/mesh/wall_meshes.hpp"

namespace drumlab::cli {

/// The file name of a mesh's scene key: "wall.lifters[0]" -> "lifters_0.stl", "wall.mesh[2]" ->
/// "mesh_2.stl".
std::string mesh_file_name(const std::string& key);

/// One line of `info` for a mesh: its key, triangles, smooth patches, where it is attached and
/// whether it is closed.
std::string mesh_summary(const WallMesh& mesh);

/// Writes every mesh as DIR/mesh_file_name(key), each atomically, creating DIR if needed; returns
/// the files. All or nothing: throws InputError naming DIR or the file if one cannot be written,
/// and removes the files this call wrote before it (and DIR, if it created it).
std::vector<std::filesystem::path> write_mesh_files(const std::vector<WallMesh>& meshes,
                                                    const std::filesystem::path& dir);

}  // namespace drumlab::cli
