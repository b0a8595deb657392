#include "app/gui/teach_steps.hpp"

#include <algorithm>

#include "engine/session/frame_snapshot.hpp"

namespace drumlab::gui {

TeachWalk::TeachWalk(const SearchVisit& visit, std::span<const Vec3> position) : visit_(visit) {
  if (visit.kind != SearchVisit::Kind::cells || visit.grids.empty()) return;
  const VisitedCells& g = visit.grids.front();
  if (g.has_own) cells_.push_back(g.own);
  cells_.insert(cells_.end(), g.forward.begin(), g.forward.end());
  cells_.insert(cells_.end(), g.backward.begin(), g.backward.end());
  for (const Index j : visit.candidates) {
    const CellCoord c = cell_containing(g.geometry, position[j]);
    const auto it = std::find(cells_.begin(), cells_.end(), c);
    cell_of_cand_.push_back(it == cells_.end() ? cells_.size() - 1
                                               : static_cast<std::size_t>(it - cells_.begin()));
  }
}

SearchVisit TeachWalk::prefix(std::size_t k) const {
  if (k >= cells_.size()) return visit_;  // the whole search, as the method counts it
  SearchVisit v = visit_;
  VisitedCells& g = v.grids.front();
  const std::size_t own = g.has_own ? 1 : 0;
  const std::size_t forward = std::min(g.forward.size(), k > own ? k - own : 0);
  const std::size_t backward =
      std::min(g.backward.size(), k > own + g.forward.size() ? k - own - g.forward.size() : 0);
  g.has_own = g.has_own && k > 0;
  g.forward.resize(forward);
  g.backward.resize(backward);
  v.candidates.clear();
  v.contacts.clear();
  for (std::size_t c = 0; c < visit_.candidates.size(); ++c) {
    if (cell_of_cand_[c] >= k) continue;
    const Index j = visit_.candidates[c];
    v.candidates.push_back(j);
    if (std::find(visit_.contacts.begin(), visit_.contacts.end(), j) != visit_.contacts.end()) {
      v.contacts.push_back(j);
    }
  }
  v.cells_visited = k;
  v.pairs_tested = v.candidates.size();
  return v;
}

TeachCounts TeachWalk::counts(std::size_t k) const {
  const SearchVisit v = prefix(k);
  return {v.cells_visited, v.candidates.size(), v.contacts.size()};
}

}  // namespace drumlab::gui
