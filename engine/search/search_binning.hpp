#pragma once
// How a search method bins the radii of a scene, in words (`drumlab info`): the cell side and
// stencil reach of the paper's grids, the levels of the multi-level grid, the Verlet list's
// builder. Read from the methods' own rules (search_methods.hpp, cell_grid.hpp,
// multilevel_grid.hpp), not measured.
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace drumlab {

/// The radii a search will see: their bounds and how many distinct values there can be.
struct RadiusRange {
  double min = 0.0;  ///< m
  double max = 0.0;  ///< m
  /// Distinct radii at most; kContinuous for a normal or lognormal class.
  std::size_t distinct = 1;
  static constexpr std::size_t kContinuous = std::numeric_limits<std::size_t>::max();
};

/// One line per fact, without the search margin (a law's reach, a Verlet skin add to it).
/// `method` is a scene's search name other than "auto"; an unknown name gives no lines.
std::vector<std::string> search_binning(std::string_view method, const RadiusRange& radii);

}  // namespace drumlab
