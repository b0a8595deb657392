#pragma once
// A multi-level (hierarchical) grid for polydisperse beds, after Ogarko & Luding (2012, Comput.
// Phys. Commun. 183): particles are split into size levels, each level has its own 3D grid with
// cells as wide as the level's largest contact distance, so every particle meets few partners per
// cell whatever the size ratio. Pairs within a level are found with a half shell of reach 1 (one
// test per pair); pairs across levels are found from the smaller particle's side, by visiting only
// the cells of the larger level that overlap a box around it of half-width r_i + R_level + margin.
#include <string>
#include <vector>

#include "engine/search/cell_index.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/half_stencil.hpp"
#include "engine/search/search_input.hpp"

namespace drumlab {

class MultiLevelGridSearch final : public ContactSearch {
 public:
  std::string_view name() const override { return "mlgrid"; }
  std::string_view description() const override {
    return "multi-level grid: a 3D grid per size level, cross-level boxes from the smaller side";
  }
  void find_pairs(const SearchInput& in, std::vector<IndexPair>& out) override;
  std::string report() const override;

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
    std::vector<CellCoord> cell;  ///< per slot
  };

  void assign_levels(const SearchInput& in);
  void lay_level(Level& level, const SearchInput& in);
  bool wrap(const Level& level, CellCoord& c) const;
  template <class Cells>
  void visit_level(const Level& level, const Cells& cells, const SearchInput& in,
                   std::vector<IndexPair>& out);
  template <class Cells>
  void visit_cross(std::size_t s_level, std::size_t slot, const Level& big, const Cells& cells,
                   const SearchInput& in, std::vector<IndexPair>& out);

  std::vector<Level> levels_;
  PairSlices slices_;  ///< per-thread pairs of visit_level()
  std::vector<std::uint8_t> level_of_;
  double slack_ = 0.0;
};

}  // namespace drumlab
