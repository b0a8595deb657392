#pragma once
// Arithmetic shared by the cell grids: the box a grid is laid over, cells per axis, and the reach
// in cells of a distance, with a bound on round-off so that a pair at exactly the cut-off distance
// is never one cell further away than the reach.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>

#include "engine/search/contact_search.hpp"

namespace drumlab {

/// The bounding box of `position` (finite), computed on the team; lo = +inf, hi = -inf if empty.
Box position_bounds(std::span<const Vec3> position);

/// The domain if given, else the particles' bounding box; z spans [0, period) when periodic.
Box search_bounds(const SearchInput& in);

/// A uniform grid of cubic cells of side b over a box.
class GridAxes {
 public:
  /// Throws InputError (naming `method`) if an axis would need more than 2^40 cells.
  GridAxes(const Box& bounds, double b, std::string_view method);

  double side() const { return b_; }
  /// Round-off bound on cell coordinates, in cells.
  double slack() const { return slack_; }
  /// Cells along axis a (>= 1): floor(extent / b) + 1, so the upper bound lies inside.
  std::int64_t cells(int a) const { return n_[a]; }
  /// Smallest k such that two points at most `reach` apart are at most k cells apart.
  int reach_cells(double reach) const {
    return static_cast<int>(std::ceil(reach / b_ * (1.0 + 8.0 * DBL_EPSILON) + slack_));
  }
  /// Cell coordinate of x along axis a, clamped to the grid.
  std::int64_t coord(double x, int a) const {
    const double u = std::floor((x - lo_[a]) / b_);
    return std::clamp<std::int64_t>(static_cast<std::int64_t>(u), 0, n_[a] - 1);
  }
  /// Unclamped cell coordinate (may lie outside the grid), with the round-off slack applied
  /// outwards in the direction `sign` (-1: lower end of a range, +1: upper end).
  std::int64_t coord_outward(double x, int a, int sign) const {
    return static_cast<std::int64_t>(std::floor((x - lo_[a]) / b_ + sign * slack_));
  }

 private:
  Vec3 lo_;
  double b_;
  std::int64_t n_[3];
  double slack_;
};

}  // namespace drumlab
