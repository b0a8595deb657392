#include "engine/search/verlet_patch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine/search/search_input.hpp"

namespace drumlab {

namespace {

/// A uniform grid over the references: cells at least `h` wide on every axis, so that two
/// references within h of each other lie in the same or neighbouring cells. Along a periodic z
/// the cells tile the period (wrapping) when at least three fit, else one cell spans it.
struct PatchGrid {
  std::array<double, 3> origin{};
  std::array<double, 3> width{};
  std::array<std::int64_t, 3> dims{1, 1, 1};
  bool wrap_z = false;

  PatchGrid(std::span<const Vec3> ref, double h, double period) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    for (const Vec3& x : ref) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    for (int a = 0; a < 3; ++a) {
      double extent = hi[a] - lo[a];
      origin[a] = lo[a];
      if (a == 2 && period > 0.0) {
        extent = period;
        origin[a] = 0.0;
      }
      dims[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(extent / h)));
      if (a == 2 && period > 0.0 && dims[a] < 3) dims[a] = 1;
    }
    wrap_z = period > 0.0 && dims[2] >= 3;
    // At most about two cells a particle: coarser on the longest axes (wider cells stay valid).
    const auto cells = [&] { return dims[0] * dims[1] * dims[2]; };
    const auto limit = static_cast<std::int64_t>(2 * ref.size() + 8);
    while (cells() > limit) {
      const auto a =
          static_cast<std::size_t>(std::max_element(dims.begin(), dims.end()) - dims.begin());
      dims[a] = a == 2 && wrap_z && dims[a] / 2 < 3 ? 1 : dims[a] / 2;
      if (a == 2 && dims[a] == 1) wrap_z = false;
    }
    for (int a = 0; a < 3; ++a) {
      const double extent = a == 2 && period > 0.0 ? period : hi[a] - lo[a];
      width[a] = extent > 0.0 ? extent / static_cast<double>(dims[a]) : h;
    }
  }

  std::int64_t coord(const Vec3& x, int a) const {
    const auto c = static_cast<std::int64_t>(std::floor((x[a] - origin[a]) / width[a]));
    return std::clamp<std::int64_t>(c, 0, dims[a] - 1);
  }
  std::uint32_t cell(std::int64_t cx, std::int64_t cy, std::int64_t cz) const {
    return static_cast<std::uint32_t>((cz * dims[1] + cy) * dims[0] + cx);
  }
  std::size_t size() const { return static_cast<std::size_t>(dims[0] * dims[1] * dims[2]); }
};

}  // namespace

void VerletPatch::find(std::span<const Vec3> ref, std::span<const double> radius,
                       std::span<const Index> moved, double reach, double period,
                       std::vector<IndexPair>& out) {
  out.clear();
  if (moved.empty()) return;
  const std::size_t n = ref.size();
  const double r_max = *std::max_element(radius.begin(), radius.end());
  const PatchGrid grid(ref, 2.0 * r_max + reach, period);
  // The particles by cell (a counting sort).
  cell_of_.resize(n);
  start_.assign(grid.size() + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& x = ref[i];
    cell_of_[i] = grid.cell(grid.coord(x, 0), grid.coord(x, 1), grid.coord(x, 2));
    ++start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 0; c < grid.size(); ++c) start_[c + 1] += start_[c];
  members_.resize(n);
  for (std::size_t i = 0; i < n; ++i) members_[start_[cell_of_[i]]++] = static_cast<Index>(i);
  for (std::size_t c = grid.size(); c > 0; --c) start_[c] = start_[c - 1];
  start_[0] = 0;
  // Each moved particle against the members of its cell and its neighbours.
  for (const Index f : moved) {
    const Vec3& x = ref[f];
    const std::int64_t c[3] = {grid.coord(x, 0), grid.coord(x, 1), grid.coord(x, 2)};
    for (std::int64_t dz = -1; dz <= 1; ++dz) {
      std::int64_t cz = c[2] + dz;
      if (grid.wrap_z) {
        cz = (cz + grid.dims[2]) % grid.dims[2];
      } else if (cz < 0 || cz >= grid.dims[2]) {
        continue;
      }
      for (std::int64_t cy = std::max<std::int64_t>(0, c[1] - 1);
           cy <= std::min(grid.dims[1] - 1, c[1] + 1); ++cy) {
        for (std::int64_t cx = std::max<std::int64_t>(0, c[0] - 1);
             cx <= std::min(grid.dims[0] - 1, c[0] + 1); ++cx) {
          const std::uint32_t cell = grid.cell(cx, cy, cz);
          for (std::uint32_t s = start_[cell]; s < start_[cell + 1]; ++s) {
            const Index j = members_[s];
            if (j == f) continue;
            const double cut = radius[f] + radius[j] + reach;
            if (distance_squared(x, ref[j], period) <= cut * cut) {
              out.push_back(f < j ? IndexPair{f, j} : IndexPair{j, f});
            }
          }
        }
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace drumlab
