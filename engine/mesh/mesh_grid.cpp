#include "engine/mesh/mesh_grid.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace drumlab {

MeshGrid::MeshGrid(const TriangleMesh& mesh, double cell, double reach) {
  if (!(cell > 0.0) || !(reach >= 0.0)) {
    throw InputError(fmt::format("{}: the mesh grid needs a positive cell", mesh.source));
  }
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  lo_ = lo - Vec3::Constant(reach);
  const Vec3 extent = hi + Vec3::Constant(reach) - lo_;
  // At most ~2 million cells: a coarser cell for a mesh much larger than the particles.
  double side = cell;
  while ((std::floor(extent.x() / side) + 1) * (std::floor(extent.y() / side) + 1) *
             (std::floor(extent.z() / side) + 1) >
         2e6) {
    side *= 2.0;
  }
  inv_cell_ = 1.0 / side;
  for (int k = 0; k < 3; ++k) n_[k] = static_cast<long>(std::floor(extent[k] * inv_cell_)) + 1;
  const auto cell_of = [&](double v, int k) {
    return std::clamp(static_cast<long>(std::floor((v - lo_[k]) * inv_cell_)), 0L, n_[k] - 1);
  };
  std::vector<std::vector<Index>> lists(static_cast<std::size_t>(n_[0] * n_[1] * n_[2]));
  for (std::size_t t = 0; t < mesh.size(); ++t) {
    Vec3 a = mesh.corner(t, 0), b = a;
    for (int k = 1; k < 3; ++k) {
      a = a.cwiseMin(mesh.corner(t, k));
      b = b.cwiseMax(mesh.corner(t, k));
    }
    a -= Vec3::Constant(reach);
    b += Vec3::Constant(reach);
    for (long i = cell_of(a.x(), 0); i <= cell_of(b.x(), 0); ++i) {
      for (long j = cell_of(a.y(), 1); j <= cell_of(b.y(), 1); ++j) {
        for (long k = cell_of(a.z(), 2); k <= cell_of(b.z(), 2); ++k) {
          lists[static_cast<std::size_t>((i * n_[1] + j) * n_[2] + k)].push_back(
              static_cast<Index>(t));
        }
      }
    }
  }
  start_.assign(lists.size() + 1, 0);
  for (std::size_t c = 0; c < lists.size(); ++c) start_[c + 1] = start_[c] + lists[c].size();
  items_.reserve(start_.back());
  for (const auto& l : lists) items_.insert(items_.end(), l.begin(), l.end());
}

std::span<const Index> MeshGrid::candidates(const Vec3& x) const {
  long c[3];
  for (int k = 0; k < 3; ++k) {
    const double f = std::floor((x[k] - lo_[k]) * inv_cell_);
    if (!(f >= 0.0) || f >= static_cast<double>(n_[k])) return {};
    c[k] = static_cast<long>(f);
  }
  const auto cell = static_cast<std::size_t>((c[0] * n_[1] + c[1]) * n_[2] + c[2]);
  return {items_.data() + start_[cell], items_.data() + start_[cell + 1]};
}

}  // namespace drumlab
