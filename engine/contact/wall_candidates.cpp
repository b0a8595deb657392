#include "engine/contact/wall_candidates.hpp"

#include <algorithm>

#include "engine/spatial_order.hpp"

namespace drumlab {

bool WallCandidates::needs_rebuild(const Particles& p, const Drum& drum, double reach) const {
  const std::size_t n = p.size();
  if (reference_.size() != n || reach != reach_) return true;
  const double limit = 0.25 * reach * reach;  // (reach / 2)^2
  const bool planar = drum.periodic();
  int moved = 0;
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for reduction(| : moved) schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    Vec3 d = p.position[i] - reference_[i];
    if (planar) d.z() = 0.0;
    moved |= !(d.squaredNorm() <= limit);  // a non-finite position rebuilds too
  }
  return moved != 0;
}

bool WallCandidates::refresh(const Particles& p, const Drum& drum, double reach,
                             WallHistory& history) {
  if (!needs_rebuild(p, drum, reach)) return false;
  const std::size_t n = p.size();
  list_.reserve(n);  // once: later builds never allocate
  list_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    // Not `gap > reach`: a NaN gap keeps the particle, so the wall loop sees it.
    if (!(drum.gap(p.position[i], p.radius[i]) > reach)) {
      list_.push_back(static_cast<Index>(i));
    } else {
      history[i].fill(Vec3::Zero());
    }
  }
  reference_.assign(p.position.begin(), p.position.end());
  reach_ = reach;
  ++rebuilds_;
  return true;
}

void WallCandidates::renumber(std::span<const Index> order, std::span<const Index> new_index) {
  if (reference_.size() != order.size()) {
    invalidate();
    return;
  }
  for (Index& i : list_) i = new_index[i];
  std::sort(list_.begin(), list_.end());
  apply_order(reference_, order, scratch_);
}

}  // namespace drumlab
