#pragma once
// The teaching mode's walk through one particle's search, cell by cell: the SearchVisit's cells in
// the order the method opens them (its own cell, then the forward half stencil, then method 2's
// far backward ring), each candidate assigned to the cell it lies in, and the running counts after
// k cells. A prefix is itself a SearchVisit, so the view draws it as it draws a whole search.
#include <cstddef>
#include <span>
#include <vector>

#include "engine/search/contact_search.hpp"

namespace drumlab::gui {

struct TeachCounts {
  std::size_t cells = 0;       ///< cells opened so far
  std::size_t candidates = 0;  ///< partners tested in them
  std::size_t contacts = 0;    ///< of which within reach
};

class TeachWalk {
 public:
  /// `visit`: a cell grid's visit (Kind::cells; others have no cells to walk and give 0 steps);
  /// `position`: the positions it was replayed on.
  TeachWalk(const SearchVisit& visit, std::span<const Vec3> position);
  /// Cells to walk (the own cell first).
  std::size_t steps() const { return cells_.size(); }
  /// The search after the first k cells, as a visit (k = steps(): the whole search; candidates
  /// outside every listed cell, e.g. across periodic ends, appear with the last cell).
  SearchVisit prefix(std::size_t k) const;
  TeachCounts counts(std::size_t k) const;

 private:
  SearchVisit visit_;
  std::vector<CellCoord> cells_;           ///< in visiting order
  std::vector<std::size_t> cell_of_cand_;  ///< index into cells_ of each candidate
};

}  // namespace drumlab::gui
