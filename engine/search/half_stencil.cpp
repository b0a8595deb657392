#include "engine/search/half_stencil.hpp"

#include <algorithm>
#include <cstdlib>

namespace drumlab {

namespace {

bool is_forward(const CellOffset& o) {
  if (o.dz != 0) return o.dz > 0;
  if (o.dy != 0) return o.dy > 0;
  return o.dx > 0;
}

int ring(const CellOffset& o) {
  return std::max({std::abs(o.dx), std::abs(o.dy), std::abs(o.dz)});
}

}  // namespace

HalfStencil::HalfStencil(int kmax, bool three_d) {
  const int kz = three_d ? kmax : 0;
  for (int dz = -kz; dz <= kz; ++dz) {
    for (int dy = -kmax; dy <= kmax; ++dy) {
      for (int dx = -kmax; dx <= kmax; ++dx) {
        const CellOffset o{dx, dy, dz};
        if (is_forward(o)) offsets.push_back(o);
      }
    }
  }
  // Stable: within a ring keep z-major, row-major order, which walks memory forward.
  std::stable_sort(offsets.begin(), offsets.end(),
                   [](const CellOffset& a, const CellOffset& b) { return ring(a) < ring(b); });
  prefix_end.assign(static_cast<std::size_t>(kmax) + 1, 0);
  for (int k = 0; k <= kmax; ++k) {
    prefix_end[k] = static_cast<std::uint32_t>(std::count_if(
        offsets.begin(), offsets.end(), [k](const CellOffset& o) { return ring(o) <= k; }));
  }
  rows.resize(static_cast<std::size_t>(kmax) + 1);
  for (int k = 1; k <= kmax; ++k) {
    std::vector<StencilRow>& r = rows[k];
    r.push_back({0, 0, 1, k});  // the rest of the own row
    for (int dy = 1; dy <= k; ++dy) r.push_back({dy, 0, -k, k});
    if (three_d) {
      for (int dz = 1; dz <= k; ++dz) {
        for (int dy = -k; dy <= k; ++dy) r.push_back({dy, dz, -k, k});
      }
    }
  }
}

std::uint64_t half_stencil_cells(int k, bool three_d) {
  const std::uint64_t w = 2 * static_cast<std::uint64_t>(k) + 1;
  return three_d ? 1 + (w * w * w - 1) / 2 : 1 + (w * w - 1) / 2;
}

}  // namespace drumlab
