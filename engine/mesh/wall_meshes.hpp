#pragma once
// The triangle walls of a scene ([[wall.mesh]] and [[wall.lifters]]) built from its keys: the STL
// files read, scaled, rotated and moved, the lifters generated, each welded into a TriangleMesh
// with its smooth patches, in the drum's frame at angle 0 (a mesh attached to the drum then turns
// with it). Every problem is a MeshWallError naming the scene key (and, for a file, the file).
#include <string>
#include <vector>

#include "engine/mesh/triangle_mesh.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab {

struct WallMesh {
  TriangleMesh mesh;
  MeshAttach attach = MeshAttach::drum;
  MeshMaterial material;
  std::string key;  ///< "wall.mesh[0]", "wall.lifters[1]"
};

/// A problem with one of the scene's meshes: its key and the reason (which names the file).
class MeshWallError : public InputError {
 public:
  MeshWallError(std::string key, std::string reason)
      : InputError(key + ": " + reason), key_(std::move(key)), reason_(std::move(reason)) {}
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string key_;
  std::string reason_;
};

/// The scene's meshes: [[wall.mesh]] in order, then [[wall.lifters]]. Throws MeshWallError for a
/// file that cannot be read (stl_file.hpp), a non-finite or degenerate triangle, a mesh that is
/// not closed where `closed = true` asks it to be, and a mesh with no part inside the drum.
std::vector<WallMesh> build_wall_meshes(const SceneConfig& scene);

/// The rotation of a [[wall.mesh]]: about x by angles[0], then y by [1], then z by [2] (degrees).
Eigen::Matrix3d mesh_rotation(const Vec3& angles_deg);

}  // namespace drumlab
