#pragma once
// A uniform cell grid with half-shell stencils, configurable as each of the paper's five methods
// (Lobovikov D.V., Kharchenko A.V., Matygullina E.V., "Comparison of efficiency of contact search
// algorithms for discrete element method", Bulletin PNRPU. Mechanical engineering, materials
// science, 2021, vol. 23, no. 2, pp. 55-61, DOI 10.15593/2224-9877/2021.2.07):
//   m1  2D grid (cells span the whole depth), cell side = R_min, per-size stencil
//   m2  as m1, and a smallest-size particle skips the far cells (see below)
//   m3  as m1 on a 3D grid (cells split along z with the same side)
//   m4  2D grid, cell side = R_max, one stencil for every particle
//   m5  as m4 on a 3D grid
//
// Where this departs from the paper's wording, and why (the paper's text, read literally, loses
// contacts or finds some twice):
// * Ranges are inclusive: the paper writes x_i - k < x_j < x_i + k, which misses partners k cells
//   away. Its own counts (41, 61, 85 cells for k = 4, 5, 6) are those of the inclusive range.
// * The reach k is ceil(reach / b) with the cell side widened by the contact margin, and a bound on
//   floating-point round-off, so a pair at exactly touching distance can never sit one cell too
//   far.
// * 3D: the paper's stencil (2D half stencil x the full z range, 779 = 41 x 19 cells) is not a half
//   shell; we use the true half shell (365 cells for k = 4), so no pair is tested twice.
// * Method 2: "a small particle does not check larger particles in the far (hatched) cells" drops
//   pairs whose larger partner lies in the small particle's forward half, because the larger
//   particle never searches backwards. Here a smallest-size particle skips its far cells entirely
//   (no small-small contact is possible there), and each larger particle additionally scans the
//   far ring of its backward half, smallest-size particles only. Every pair is still tested once.
#include <cstdint>
#include <vector>

#include "engine/search/cell_index.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/half_stencil.hpp"
#include "engine/search/search_input.hpp"

namespace drumlab {

struct CellGridConfig {
  const char* name = "";
  const char* description = "";
  bool three_d = false;                ///< split cells along z as well
  bool cell_from_min_radius = true;    ///< cell side R_min (else R_max)
  bool per_size_stencil = true;        ///< reach r_i + R_max (else 2 R_max for everyone)
  bool skip_far_for_smallest = false;  ///< method 2
};

/// Configuration of the paper's method 1..5. Throws InputError for another number.
CellGridConfig paper_method(int method);

/// One particle's search in the last call, cell by cell, as the hot loop did it (for pictures and
/// teaching; O(N) per call). cells_visited() and candidates.size() equal the per-particle counters.
struct SearchTrace {
  CellCoord own{0, 0, 0};
  std::vector<CellCoord> forward;   ///< forward half-shell cells visited, own cell excluded
  std::vector<CellCoord> backward;  ///< method 2: far backward cells scanned for smallest partners
  std::vector<Index> candidates;    ///< particles whose distance was computed (original indices)
  std::vector<Index> contacts;      ///< candidates within the cut-off
  int reach = 0;                    ///< forward reach in cells
  std::size_t cells_visited() const { return 1 + forward.size() + backward.size(); }
};

class CellGridSearch final : public ContactSearch {
 public:
  explicit CellGridSearch(const CellGridConfig& config) : config_(config) {}

  std::string_view name() const override { return config_.name; }
  std::string_view description() const override { return config_.description; }
  void find_pairs(const SearchInput& in, std::vector<IndexPair>& out) override;
  double cell_size() const override { return geometry_.cell_xy; }

  const CellGridConfig& config() const { return config_; }
  const GridGeometry& geometry() const { return geometry_; }
  /// Stencil reach in cells of particle i (original index) in the last call.
  int reach_cells(Index i) const { return reach_[i]; }
  /// Cell of particle i (original index) in the last call.
  const CellCoord& cell_of(Index i) const { return cell_[i]; }
  /// Replays particle i's search of the last call (original index). Throws InputError if i is out
  /// of range.
  SearchTrace trace(Index i) const;
  /// The trace as a SearchVisit (kind cells). The positions of `in` are not read: the last
  /// call's are.
  SearchVisit visit(Index i, const SearchInput& in) const override;

 private:
  void lay_grid(const SearchInput& in);
  void sort_into_cells(const SearchInput& in);
  void build_hashed();
  bool wrap(CellCoord& c) const;
  bool find_cell(const CellCoord& c, CellRange& r) const;
  template <class Cells>
  void visit_all(const Cells& cells, const SearchInput& in, std::vector<IndexPair>& out);

  CellGridConfig config_;
  GridGeometry geometry_;
  HalfStencil stencil_;
  bool stencil_three_d_ = false;
  int k_small_ = 0;          ///< reach of smallest-size pairs (method 2)
  double small_radius_ = 0;  ///< radius at or below which a particle counts as smallest-size
  double margin_ = 0.0;      ///< margin and z period of the last call (for trace())
  double period_ = 0.0;
  // Per original index.
  std::vector<int> reach_;
  std::vector<int> reach_back_;  ///< method 2: backward reach towards smallest-size particles
  std::vector<CellCoord> cell_;
  // Per slot of the cell-sorted order.
  std::vector<Index> order_;
  std::vector<Vec3> sorted_position_;
  std::vector<double> sorted_radius_;
  std::vector<std::uint32_t> scratch_;
  PairSlices slices_;  ///< per-thread pairs of visit_all
  DenseCellIndex dense_;
  HashedCellIndex hashed_;
};

}  // namespace drumlab
