#include "engine/mesh/mesh_wall_set.hpp"

#include <cmath>

namespace drumlab {

MeshWallSet::MeshWallSet(std::vector<WallMesh> meshes, double cell, double reach) {
  walls_.reserve(meshes.size());
  for (WallMesh& m : meshes) {
    MeshGrid grid(m.mesh, cell, reach);
    const Index first = patches_;
    patches_ += m.mesh.patches;
    const bool closed = is_closed(m.mesh);
    walls_.push_back(Wall{std::move(m), std::move(grid), first, closed});
  }
}

void MeshWallSet::contacts(const Vec3& x, double r, double c, double s, Scratch& scratch,
                           std::vector<MeshContact>& out) const {
  out.clear();
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    const Wall& w = walls_[k];
    const bool turns = w.mesh.attach == MeshAttach::drum;
    // The drum's frame at angle 0: x turned back by the drum's angle.
    const Vec3 q = turns ? Vec3(c * x.x() + s * x.y(), c * x.y() - s * x.x(), x.z()) : x;
    const std::span<const Index> candidates = w.grid.candidates(q);
    if (candidates.empty()) continue;
    patch_contacts(w.mesh.mesh, candidates, q, r, scratch.patch);
    for (const PatchContact& pc : scratch.patch) {
      MeshContact m;
      m.wall = static_cast<std::uint32_t>(k);
      m.patch = w.first_patch + pc.patch;
      m.overlap = pc.overlap;
      if (turns) {
        m.normal = Vec3(c * pc.normal.x() - s * pc.normal.y(),
                        s * pc.normal.x() + c * pc.normal.y(), pc.normal.z());
        m.point = Vec3(c * pc.point.x() - s * pc.point.y(), s * pc.point.x() + c * pc.point.y(),
                       pc.point.z());
      } else {
        m.normal = pc.normal;
        m.point = pc.point;
      }
      out.push_back(m);
    }
  }
}

bool MeshWallSet::blocks(const Vec3& x, double r, Scratch& scratch,
                         std::vector<MeshContact>& hits) const {
  contacts(x, r, 1.0, 0.0, scratch, hits);
  if (!hits.empty()) return true;
  for (const Wall& w : walls_) {
    if (w.closed && std::abs(winding_number(w.mesh.mesh, x)) > 0.5) return true;
  }
  return false;
}

}  // namespace drumlab
