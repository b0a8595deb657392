#include "engine/search/verlet_patch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine/counting_sort.hpp"
#include "engine/parallel_copy.hpp"
#include "engine/search/grid_axes.hpp"
#include "engine/search/search_input.hpp"
#include "engine/threads.hpp"

namespace drumlab {

namespace {

/// A uniform grid over the references: cells at least `h` wide on every axis, so that two
/// references within k h of each other lie within k cells of each other on every axis. Along a
/// periodic z the cells tile the period (wrapping) when at least three fit, else one cell spans
/// it.
struct PatchGrid {
  std::array<double, 3> origin{};
  std::array<double, 3> width{};
  std::array<std::int64_t, 3> dims{1, 1, 1};
  bool wrap_z = false;

  PatchGrid(std::span<const Vec3> ref, double h, double period) {
    const Box bounds = position_bounds(ref);
    const Vec3& lo = bounds.lo;
    const Vec3& hi = bounds.hi;
    for (int a = 0; a < 3; ++a) {
      double extent = hi[a] - lo[a];
      origin[a] = lo[a];
      if (a == 2 && period > 0.0) {
        extent = period;
        origin[a] = 0.0;
      }
      // At most 2^20 a side before the cap below (a particle far out must not overflow it).
      dims[a] = static_cast<std::int64_t>(std::clamp(std::floor(extent / h), 1.0, 1048576.0));
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
                       std::span<const Index> moved, double margin, double period,
                       std::vector<IndexPair>& out) {
  out.clear();
  if (moved.empty()) return;
  const std::size_t n = ref.size();
  const double r_max = *std::max_element(radius.begin(), radius.end());
  // Cells half the widest pair's cut-off: a moved particle visits the cells within its own reach
  // (five a side at most), about half the volume three cells of the full cut-off a side would hold.
  const double widest = pair_cutoff(r_max, r_max, margin);
  const PatchGrid grid(ref, 0.5 * widest, period);
  const std::size_t cells = grid.size();
  // The references by cell, with their radii, in one contiguous copy (a counting sort).
  cell_of_.resize(n);
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (count >= kParallelMinElements)
  for (std::int64_t i = 0; i < count; ++i) {
    const Vec3& x = ref[i];
    cell_of_[i] = grid.cell(grid.coord(x, 0), grid.coord(x, 1), grid.coord(x, 2));
  }
  members_.resize(n);
  sorted_.resize(n);
  const std::size_t shares = counting_sort_by_row(
      n, cells, kParallelMinElements, fill_, [&](std::size_t i) { return cell_of_[i]; },
      [&](std::size_t i, std::uint32_t slot) {
        members_[slot] = static_cast<Index>(i);
        sorted_[slot] = {ref[i].x(), ref[i].y(), ref[i].z(), radius[i]};
      });
  const auto cell_end = [&](std::size_t c) { return fill_[c * shares + shares - 1]; };
  const auto cell_begin = [&](std::size_t c) { return c == 0 ? 0u : cell_end(c - 1); };
  // Each moved particle against the members of its cell and its neighbours, the moved particles
  // in contiguous shares (the output is sorted after).
  const int threads = slices_.prepare(moved.size() >= 256 ? max_threads() : 1);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int share = 0; share < threads; ++share) {
    std::vector<IndexPair>& found = slices_.slice(share);
    const std::size_t m = moved.size();
    const std::size_t begin =
        m * static_cast<std::size_t>(share) / static_cast<std::size_t>(threads);
    const std::size_t end =
        m * static_cast<std::size_t>(share + 1) / static_cast<std::size_t>(threads);
    for (std::size_t q = begin; q < end; ++q) {
      const Index f = moved[q];
      const Vec3& x = ref[f];
      const std::int64_t c[3] = {grid.coord(x, 0), grid.coord(x, 1), grid.coord(x, 2)};
      const double own = pair_cutoff(radius[f], r_max, margin);  // f's farthest partner
      std::int64_t range[3];
      for (int a = 0; a < 3; ++a) {
        range[a] = static_cast<std::int64_t>(std::ceil(own / grid.width[a]));
      }
      // Along a wrapped z, each cell once.
      const bool all_z = grid.wrap_z && 2 * range[2] + 1 >= grid.dims[2];
      const std::int64_t z0 = all_z ? 0 : c[2] - range[2];
      const std::int64_t z1 = all_z ? grid.dims[2] - 1 : c[2] + range[2];
      for (std::int64_t z = z0; z <= z1; ++z) {
        std::int64_t cz = z;
        if (grid.wrap_z) {
          cz = ((z % grid.dims[2]) + grid.dims[2]) % grid.dims[2];
        } else if (cz < 0 || cz >= grid.dims[2]) {
          continue;
        }
        for (std::int64_t cy = std::max<std::int64_t>(0, c[1] - range[1]);
             cy <= std::min(grid.dims[1] - 1, c[1] + range[1]); ++cy) {
          // The row's cells along x are one contiguous range of slots.
          const std::int64_t x0 = std::max<std::int64_t>(0, c[0] - range[0]);
          const std::int64_t x1 = std::min(grid.dims[0] - 1, c[0] + range[0]);
          const std::uint32_t s0 = cell_begin(grid.cell(x0, cy, cz));
          const std::uint32_t s1 = cell_end(grid.cell(x1, cy, cz));
          for (std::uint32_t s = s0; s < s1; ++s) {
            const PackedSphere& o = sorted_[s];
            const double cut = pair_cutoff(radius[f], o.r, margin);
            const double dx = x.x() - o.x, dy = x.y() - o.y;
            const double dz2 = nearest_image_z(x.z() - o.z, period);
            if (dx * dx + dy * dy + dz2 * dz2 <= cut * cut && members_[s] != f) {
              const Index j = members_[s];
              found.push_back(f < j ? IndexPair{f, j} : IndexPair{j, f});
            }
          }
        }
      }
    }
  }
  slices_.join(out);
  sort_pairs(out, n, scratch_, counts_);
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace drumlab
