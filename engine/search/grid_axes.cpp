#include "engine/search/grid_axes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <limits>

#include "engine/parallel_copy.hpp"

namespace drumlab {

namespace {

/// Cells along one axis are capped so that cell coordinates stay exact in doubles and int64.
constexpr double kMaxCellsPerAxis = 1099511627776.0;  // 2^40

}  // namespace

Box position_bounds(std::span<const Vec3> position) {
  // The extremes of each coordinate, on every thread (a minimum does not depend on the order of
  // the comparisons; the positions must be finite).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo[3] = {kInf, kInf, kInf};
  double hi[3] = {-kInf, -kInf, -kInf};
  const auto n = static_cast<std::int64_t>(position.size());
  // clang-format off
#pragma omp parallel for schedule(static) if (n >= kParallelMinElements) \
    reduction(min : lo[:3]) reduction(max : hi[:3])
  // clang-format on
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec3& x = position[static_cast<std::size_t>(i)];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], x[a]);
      hi[a] = std::max(hi[a], x[a]);
    }
  }
  Box box;
  box.lo = Vec3(lo[0], lo[1], lo[2]);
  box.hi = Vec3(hi[0], hi[1], hi[2]);
  return box;
}

Box search_bounds(const SearchInput& in) {
  Box box;
  if (in.domain) {
    box = *in.domain;
  } else if (!in.position.empty()) {
    box = position_bounds(in.position);
  }
  if (in.period_z) {
    box.lo.z() = 0.0;
    box.hi.z() = *in.period_z;
  }
  return box;
}

GridAxes::GridAxes(const Box& bounds, double b, std::string_view method) : lo_(bounds.lo), b_(b) {
  double largest = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double cells = (bounds.hi[a] - bounds.lo[a]) / b;
    if (!(cells < kMaxCellsPerAxis)) {
      throw InputError(fmt::format(
          "search {}: particles span {:.6g} m along {} = {:.3g} cells of side {:.6g} m; too many "
          "to index",
          method, bounds.hi[a] - bounds.lo[a], "xyz"[a], cells, b));
    }
    n_[a] = static_cast<std::int64_t>(cells) + 1;
    largest = std::max(largest, cells);
  }
  // Cell coordinates carry an error of a few ulps of the largest coordinate, in cells.
  const double scale =
      std::max(bounds.lo.cwiseAbs().maxCoeff(), bounds.hi.cwiseAbs().maxCoeff()) / b + largest;
  slack_ = 16.0 * DBL_EPSILON * (scale + 1.0);
}

}  // namespace drumlab
