#include "engine/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (const Vec3& x : position) lo = lo.cwiseMin(x);
  b.keys.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    b.keys[i] = {morton_key(position[i], lo, cell), static_cast<Index>(i)};
  }
  std::sort(b.keys.begin(), b.keys.end());
  b.order.resize(n);
  b.new_index.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    b.order[k] = b.keys[k].second;
    b.new_index[b.order[k]] = static_cast<Index>(k);
  }
}

}  // namespace drumlab
