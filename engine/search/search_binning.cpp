#include "engine/search/search_binning.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/search/cell_grid.hpp"
#include "engine/search/multilevel_grid.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab {
namespace {

int cells(double reach, double side) {
  return static_cast<int>(std::ceil(reach / side * (1.0 - 1e-12)));
}

/// The paper's grid `config`: its cell side and each particle's stencil reach.
void paper_grid_lines(const CellGridConfig& config, const RadiusRange& r,
                      std::vector<std::string>& out) {
  const double side = config.cell_from_min_radius ? r.min : r.max;
  out.push_back(fmt::format("{} cells of side {} = {:.4g} m{}", config.three_d ? "3D" : "2D",
                            config.cell_from_min_radius ? "r_min" : "r_max", side,
                            config.three_d ? "" : " spanning the depth"));
  if (config.per_size_stencil) {
    out.push_back(fmt::format(
        "per-size stencil: particle i reaches r_i + r_max, {} to {} cells each way (r_i = {:.4g} "
        "to {:.4g} m)",
        cells(r.min + r.max, side), cells(2.0 * r.max, side), r.min, r.max));
  } else {
    out.push_back(fmt::format("one stencil for all: reach 2 r_max = {:.4g} m, {} cells each way",
                              2.0 * r.max, cells(2.0 * r.max, side)));
  }
  if (config.skip_far_for_smallest) {
    out.push_back(fmt::format(
        "particles of radius r_min skip the cells beyond 2 r_min ({} cells){}",
        cells(2 * r.min, side),
        r.distinct == RadiusRange::kContinuous ? " (a continuous distribution has about one)"
                                               : ""));
  }
}

/// The multi-level grid's levels: one per distinct radius, or factor-of-2 bins from r_min.
void level_lines(const RadiusRange& r, std::vector<std::string>& out) {
  if (r.distinct <= kMaxExactLevels) {
    out.push_back(fmt::format(
        "{} distinct radii at most -> one level each, a 3D grid of cells about the level's "
        "diameter",
        r.distinct));
    return;
  }
  const int levels = static_cast<int>(std::floor(std::log2(r.max / r.min))) + 1;
  out.push_back(fmt::format(
      "more than {} distinct radii -> levels by factors of 2 from the smallest radius present: "
      "at most {} level{}",
      kMaxExactLevels, levels, levels == 1 ? "" : "s"));
  for (int l = 0; l < levels; ++l) {
    const double lo = std::ldexp(r.min, l);
    const double hi = std::min(std::ldexp(r.min, l + 1), r.max);
    out.push_back(fmt::format("  level {}: r in [{:.4g}, {:.4g}{} m, cells <= {:.4g} m", l, lo, hi,
                              l + 1 == levels ? "]" : ")", 2.0 * hi));
  }
}

}  // namespace

std::vector<std::string> search_binning(std::string_view method, const RadiusRange& radii) {
  const auto parsed = parse_search_method(method);
  std::vector<std::string> out;
  if (!parsed) return out;
  const SearchMethodInfo& m = *parsed->method;
  if (parsed->verlet) out.push_back(fmt::format("Verlet list rebuilt by {}:", m.name));
  if (m.cell == CellRule::none) {
    out.push_back("no grid: every pair is tested");
  } else if (m.cell == CellRule::per_level) {
    level_lines(radii, out);
  } else {
    paper_grid_lines(paper_method(m.name[1] - '0'), radii, out);
  }
  return out;
}

}  // namespace drumlab
