#pragma once
// A scene's triangle walls at run time: each mesh with its candidate grid (mesh_grid.hpp, built
// once in the mesh's own frame), and the query the force loop makes for one sphere: its contacts
// with every mesh, one per smooth patch (patch_contact.hpp), in the frame the particles live in.
// A mesh attached to the drum is queried with the sphere's position turned back by the drum's
// angle, and its contact turned forward again; a mesh fixed in the lab is queried as it stands.
#include <span>
#include <vector>

#include "engine/mesh/mesh_grid.hpp"
#include "engine/mesh/patch_contact.hpp"
#include "engine/mesh/wall_meshes.hpp"

namespace drumlab {

/// One sphere's contact with a patch of a mesh, in the particles' frame.
struct MeshContact {
  std::uint32_t wall = 0;  ///< the mesh (WallMesh order)
  Index patch = 0;         ///< numbered across all meshes: the history's key
  Vec3 normal = Vec3::Zero();
  Vec3 point = Vec3::Zero();
  double overlap = 0.0;
};

class MeshWallSet {
 public:
  MeshWallSet() = default;
  /// `cell`: the grids' cell side (m); `reach`: the largest radius a query may have (m).
  MeshWallSet(std::vector<WallMesh> meshes, double cell, double reach);

  bool empty() const { return walls_.empty(); }
  std::size_t size() const { return walls_.size(); }
  const WallMesh& wall(std::size_t k) const { return walls_[k].mesh; }
  /// The patches of all meshes together.
  Index patches() const { return patches_; }

  /// Scratch of one thread's queries.
  struct Scratch {
    std::vector<PatchContact> patch;
  };
  /// The contacts of the sphere (centre x, radius r <= reach) with every mesh, the drum turned
  /// by the angle whose cosine and sine are c, s; by increasing patch number. `out` is replaced.
  void contacts(const Vec3& x, double r, double c, double s, Scratch& scratch,
                std::vector<MeshContact>& out) const;
  /// Whether a sphere at x (the drum at angle 0) touches a mesh or lies inside a closed one: a
  /// place a fill must not put a particle.
  bool blocks(const Vec3& x, double r, Scratch& scratch, std::vector<MeshContact>& hits) const;

 private:
  struct Wall {
    WallMesh mesh;
    MeshGrid grid;
    Index first_patch;
    bool closed;
  };
  std::vector<Wall> walls_;
  Index patches_ = 0;
};

}  // namespace drumlab
