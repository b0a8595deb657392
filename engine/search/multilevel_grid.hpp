#pragma once
// A multi-level (hierarchical) grid for polydisperse beds, after Ogarko & Luding (2012, Comput.
// Phys. Commun. 183): particles are split into size levels, each level has its own 3D grid with
// cells as wide as the level's largest contact distance, so every particle meets few partners per
// cell whatever the size ratio. Pairs within a level are found with a half shell of reach 1 (one
// test per pair). Pairs across levels are found from the larger particle's side: it visits the
// cells of each smaller level within r_i + R_level + margin of it, row by row, each row cut to the
// chord of that sphere. From the larger side there are fewer particles to search from (600 large
// against 16,200 small in the demo drum) and longer rows each: measured, the rows visited per
// build fell about fourfold and the pairs tested stayed about the same.
#include <string>
#include <vector>

#include "engine/search/cell_index.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/half_stencil.hpp"
#include "engine/search/search_input.hpp"

namespace drumlab {

class GridAxes;

/// Up to this many distinct radii get a level each; beyond (a size distribution), level
/// floor(log2(r / r_min)) holds the radii in [2^l r_min, 2^(l+1) r_min).
inline constexpr std::size_t kMaxExactLevels = 8;

class MultiLevelGridSearch final : public ContactSearch {
 public:
  std::string_view name() const override { return "mlgrid"; }
  std::string_view description() const override;
  void find_pairs(const SearchInput& in, std::vector<IndexPair>& out) override;
  std::string report() const override;
  /// Own level: own cell and half shell; each smaller level: the cells within reach of i. The
  /// positions of `in` are not read: the last call's are.
  SearchVisit visit(Index i, const SearchInput& in) const override;

  /// Levels laid in the last call.
  std::size_t levels() const { return levels_.size(); }

 private:
  struct Level {
    double rmax = 0.0;  ///< largest radius in the level
    Vec3 origin = Vec3::Zero();
    double b = 0.0, bz = 0.0;  ///< cell side in x, y and along z
    std::int64_t n[3] = {1, 1, 1};
    int k = 1;  ///< same-level reach in cells
    bool periodic = false;
    bool hashed = false;
    HalfStencil stencil;
    DenseCellIndex dense;
    HashedCellIndex hashed_index;
    std::vector<Index> order;  ///< slot -> particle
    std::vector<Vec3> position;
    std::vector<double> radius;
    std::vector<CellCoord> cell;          ///< per slot
    std::vector<CellCoord> scratch_cell;  ///< lay_level's buffers, kept between calls
    std::vector<std::size_t> scratch_perm;
    std::vector<Index> scratch_order;
    SortedParticles sorted() const { return {position.data(), radius.data(), order.data()}; }
  };

  void assign_levels(const SearchInput& in);
  /// Lays the level's grid over `bounds` and sorts its members into it, in these steps:
  void lay_level(Level& level, const SearchInput& in, const Box& bounds);
  void size_level(Level& level, const GridAxes& axes, double reach, const Box& bounds,
                  const SearchInput& in);
  static void bin_members(Level& level, const GridAxes& axes, const SearchInput& in);
  static void sort_members(Level& level);
  static void gather_members(Level& level, const SearchInput& in);
  static void index_hashed_cells(Level& level);
  bool wrap(const Level& level, CellCoord& c) const;
  template <class Cells>
  void visit_level(const Level& level, const Cells& cells, const SearchInput& in,
                   std::vector<IndexPair>& out);
  /// Calls row(x0, x1, y, z) for every row of cells [x0, x1] of level `small` that may hold a
  /// partner of the particle at xi with radius ri (margin: the search's, plus the tolerance).
  template <class Row>
  void cross_rows(const Level& small, const Vec3& xi, double ri, double margin, Row&& row) const;
  static bool find_cell(const Level& level, const CellCoord& c, CellRange& r);
  static GridGeometry geometry_of(const Level& level);
  template <class Cells>
  void visit_cross(const Level& level, std::size_t slot, const Level& small, const Cells& cells,
                   const SearchInput& in, std::vector<IndexPair>& out);

  std::vector<Level> levels_;
  PairSlices slices_;             ///< per-thread pairs of visit_level()
  std::vector<double> distinct_;  ///< assign_levels' buffers
  std::vector<int> raw_;
  std::vector<int> compact_;
  std::vector<Index> level_members_;  ///< the particles by level (assign_levels)
  std::vector<std::uint32_t> level_fill_;
  double slack_ = 0.0;
  double margin_ = 0.0;  ///< margin and z period of the last call (for visit())
  double period_ = 0.0;
};

}  // namespace drumlab
