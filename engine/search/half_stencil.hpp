#pragma once
// Half-shell cell stencils. A particle searches its own cell (partners later in cell order) and the
// "forward" half of the cells around it; the other half is covered from the partner's side, so each
// pair is tested once (Newton's third law).
//
// Forward half, as in the paper's figure 1 for 2D: the cells to the right in the same row, and
// every cell of the rows above. In 3D the paper takes that 2D half stencil times the full z range,
// which is not a half shell (pairs in the same column but different layers are found twice); we
// use the true half shell: (dz > 0) or (dz == 0 and dy > 0) or (dz == 0, dy == 0, dx > 0).
#include <cstdint>
#include <vector>

namespace drumlab {

struct CellOffset {
  std::int32_t dx, dy, dz;
};

/// A run of cells along x at fixed (dy, dz): with x fastest in memory it is one contiguous slice
/// of the cell-sorted particles, so a dense grid reads it with two lookups instead of one per cell.
struct StencilRow {
  std::int32_t dy, dz, dx_lo, dx_hi;
};

/// Forward half-shell offsets within Chebyshev distance kmax (own cell excluded), sorted by ring
/// (Chebyshev distance) so the offsets within distance k form a prefix of length prefix_end[k].
struct HalfStencil {
  std::vector<CellOffset> offsets;
  std::vector<std::uint32_t> prefix_end;      ///< size kmax + 1; prefix_end[0] == 0
  std::vector<std::vector<StencilRow>> rows;  ///< rows[k]: the same half shell of reach k as rows

  HalfStencil() = default;
  HalfStencil(int kmax, bool three_d);
  int kmax() const { return static_cast<int>(prefix_end.size()) - 1; }
};

/// Number of cells in a half stencil of reach k, own cell included: 1 + k + k(2k+1) in 2D,
/// 1 + ((2k+1)^3 - 1) / 2 in 3D.
std::uint64_t half_stencil_cells(int k, bool three_d);

}  // namespace drumlab
