#pragma once
// The wall-candidate structure of a mesh: a uniform grid over the mesh's bounding box, each
// cell listing (ascending) the triangles whose bounding box, grown by `reach`, overlaps it. A
// sphere of radius <= reach whose centre lies in a cell can touch only the triangles listed
// there. Built once in the mesh's own frame (a mesh that turns with the drum is queried with
// the particle's position in the drum's frame), so it is never rebuilt while the mesh moves.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/triangle_mesh.hpp"

namespace drumlab {

class MeshGrid {
 public:
  /// `cell`: the cell's side (m, > 0; e.g. two largest diameters); `reach`: the largest radius.
  MeshGrid(const TriangleMesh& mesh, double cell, double reach);
  /// The triangles a sphere centred at x (radius <= reach) may touch; empty far from the mesh.
  std::span<const Index> candidates(const Vec3& x) const;
  std::size_t cells() const { return start_.empty() ? 0 : start_.size() - 1; }

 private:
  Vec3 lo_ = Vec3::Zero();
  double inv_cell_ = 0.0;
  std::array<long, 3> n_{};
  std::vector<std::size_t> start_;  ///< CSR rows per cell
  std::vector<Index> items_;
  /// One bit per cell: whether it lists any triangle. Most particles stand in empty cells; the
  /// bits fit a core's first-level cache where the rows do not.
  std::vector<std::uint64_t> occupied_;
};

}  // namespace drumlab
