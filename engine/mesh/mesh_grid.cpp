#include "engine/mesh/mesh_grid.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/mesh/patch_contact.hpp"

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
    // Of the cells the grown box overlaps, those whose centre lies within reach + half the
    // cell's diagonal of the triangle itself (a blade set at an angle fills few cells of its box).
    const double near = reach + 0.5 * std::sqrt(3.0) * side;
    for (long i = cell_of(a.x(), 0); i <= cell_of(b.x(), 0); ++i) {
      for (long j = cell_of(a.y(), 1); j <= cell_of(b.y(), 1); ++j) {
        for (long k = cell_of(a.z(), 2); k <= cell_of(b.z(), 2); ++k) {
          const Vec3 centre =
              lo_ + side * Vec3(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5,
                                static_cast<double>(k) + 0.5);
          const Vec3 q =
              nearest_on_triangle(centre, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2))
                  .point;
          if ((q - centre).squaredNorm() > near * near) continue;
          lists[static_cast<std::size_t>((i * n_[1] + j) * n_[2] + k)].push_back(
              static_cast<Index>(t));
        }
      }
    }
  }
  start_.assign(lists.size() + 1, 0);
  for (std::size_t c = 0; c < lists.size(); ++c) start_[c + 1] = start_[c] + lists[c].size();
  items_.reserve(start_.back());
  occupied_.assign((lists.size() + 63) / 64, 0);
  for (std::size_t c = 0; c < lists.size(); ++c) {
    items_.insert(items_.end(), lists[c].begin(), lists[c].end());
    if (!lists[c].empty()) occupied_[c / 64] |= std::uint64_t{1} << (c % 64);
  }
}

std::span<const Index> MeshGrid::candidates(const Vec3& x) const {
  long c[3];
  for (int k = 0; k < 3; ++k) {
    const double f = std::floor((x[k] - lo_[k]) * inv_cell_);
    if (!(f >= 0.0) || f >= static_cast<double>(n_[k])) return {};
    c[k] = static_cast<long>(f);
  }
  const auto cell = static_cast<std::size_t>((c[0] * n_[1] + c[1]) * n_[2] + c[2]);
  if ((occupied_[cell / 64] >> (cell % 64) & 1) == 0) return {};
  return {items_.data() + start_[cell], items_.data() + start_[cell + 1]};
}

}  // namespace drumlab
