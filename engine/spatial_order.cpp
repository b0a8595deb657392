#include "engine/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/threads.hpp"

namespace drumlab {

namespace {

/// Spreads the low 21 bits of v so that two zero bits follow each bit.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// Where the first p entries of the merge of the sorted runs a and b (unique values) end in a:
/// the merge path's crossing of diagonal p (Odeh, Green, Mwassi, Shmueli and Birk, 2012).
template <class T>
std::size_t merge_split(std::span<const T> a, std::span<const T> b, std::size_t p) {
  std::size_t lo = p > b.size() ? p - b.size() : 0;
  std::size_t hi = std::min(p, a.size());
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (a[mid] < b[p - mid - 1]) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return lo;
}

/// Sorts `v` (unique values, so every correct sort gives the same order) on the threads at hand
/// without allocating once `scratch` has grown: one run per thread sorted at once, then rounds
/// of merges of neighbouring runs, each merge shared by the threads along its merge path.
template <class T>
void sort_unique(std::vector<T>& v, std::vector<T>& scratch) {
  constexpr std::size_t kPerThread = 4096;  // below this, one thread
  const std::size_t n = v.size();
  const auto runs = static_cast<std::size_t>(
      std::clamp<std::size_t>(n / kPerThread, 1, static_cast<std::size_t>(max_threads())));
  if (runs == 1) {
    std::sort(v.begin(), v.end());
    return;
  }
  scratch.resize(n);
  const auto run_start = [&](std::size_t r) { return n * std::min(r, runs) / runs; };
  T* from = v.data();
  T* to = scratch.data();
  const auto count = static_cast<std::int64_t>(runs);
  const int team = static_cast<int>(runs);
  // Work is shared by run and by slice of a merge's output, not by thread number, so a team
  // smaller than asked for (a nested region) still does all of it.
#pragma omp parallel num_threads(team)
  {
#pragma omp for schedule(static)
    for (std::int64_t r = 0; r < count; ++r) {
      std::sort(from + run_start(static_cast<std::size_t>(r)),
                from + run_start(static_cast<std::size_t>(r) + 1));
    }
    for (std::size_t width = 1; width < runs; width *= 2) {
      for (std::size_t g = 0; g < runs; g += 2 * width) {
        const std::size_t a0 = run_start(g);
        const std::size_t b0 = run_start(g + width);
        const std::size_t end = run_start(g + 2 * width);
        const std::span<const T> a(from + a0, b0 - a0);
        const std::span<const T> b(from + b0, end - b0);
#pragma omp for schedule(static)
        for (std::int64_t slice = 0; slice < count; ++slice) {
          const auto q = static_cast<std::size_t>(slice);
          const std::size_t p0 = (end - a0) * q / runs;
          const std::size_t p1 = (end - a0) * (q + 1) / runs;
          const std::size_t i0 = merge_split(a, b, p0);
          const std::size_t i1 = merge_split(a, b, p1);
          std::merge(a.begin() + static_cast<std::ptrdiff_t>(i0),
                     a.begin() + static_cast<std::ptrdiff_t>(i1),
                     b.begin() + static_cast<std::ptrdiff_t>(p0 - i0),
                     b.begin() + static_cast<std::ptrdiff_t>(p1 - i1), to + a0 + p0);
        }
      }
#pragma omp single
      std::swap(from, to);
    }
  }
  if (from != v.data()) v.swap(scratch);
}

}  // namespace

std::uint64_t morton_key(const Vec3& x, const Vec3& lo, double cell) {
  // Cells beyond 2^21 per axis share the last code: the order is then only coarser, still valid.
  constexpr double kMaxCell = (1 << 21) - 1;
  const auto coord = [&](double v, double origin) {
    return static_cast<std::uint64_t>(std::clamp(std::floor((v - origin) / cell), 0.0, kMaxCell));
  };
  return spread_bits(coord(x.x(), lo.x())) | spread_bits(coord(x.y(), lo.y())) << 1 |
         spread_bits(coord(x.z(), lo.z())) << 2;
}

void morton_order(std::span<const Vec3> position, double cell, ReorderBuffers& b) {
  const std::size_t n = position.size();
  const auto count = static_cast<std::int64_t>(n);
  // Each thread's smallest corner, then theirs: a minimum is exact in any order.
  const int threads = max_threads();
  std::vector<Vec3>& lows = b.lows;
  lows.assign(static_cast<std::size_t>(threads),
              Vec3::Constant(std::numeric_limits<double>::infinity()));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    Vec3& lo = lows[static_cast<std::size_t>(thread_number())];
    lo = lo.cwiseMin(position[static_cast<std::size_t>(i)]);
  }
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (const Vec3& l : lows) lo = lo.cwiseMin(l);
  b.keys.resize(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    b.keys[k] = {morton_key(position[k], lo, cell), static_cast<Index>(k)};
  }
  sort_unique(b.keys, b.sorted);
  b.order.resize(n);
  b.new_index.resize(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    b.order[k] = b.keys[k].second;
    b.new_index[b.order[k]] = static_cast<Index>(k);
  }
}

}  // namespace drumlab
