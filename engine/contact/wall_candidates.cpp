#include "engine/contact/wall_candidates.hpp"

#include <algorithm>
#include <cmath>

#include "engine/spatial_order.hpp"

namespace drumlab {

bool WallCandidates::needs_rebuild(const Particles& p, const Drum& drum, double reach) {
  const std::size_t n = p.size();
  if (reference_.size() != n || reach != reach_) return true;
  if (moved_ <= reach) return false;  // no particle can have closed its gap of more than reach
  ++checks_;
  const bool planar = drum.periodic();
  double largest = 0.0;
  int non_finite = 0;
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for reduction(max : largest) reduction(| : non_finite) schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    Vec3 d = p.position[i] - reference_[i];
    if (planar) d.z() = 0.0;
    const double d2 = d.squaredNorm();
    non_finite |= !std::isfinite(d2);  // a non-finite position rebuilds
    largest = std::max(largest, d2);
  }
  moved_ = non_finite != 0 ? std::numeric_limits<double>::infinity() : std::sqrt(largest);
  return !(moved_ <= reach);
}

bool WallCandidates::refresh(const Particles& p, const Drum& drum, double reach,
                             WallHistory& history, double moved) {
  moved_ += moved >= 0.0 ? moved : std::numeric_limits<double>::infinity();  // NaN: unknown
  if (!needs_rebuild(p, drum, reach)) return false;
  const std::size_t n = p.size();
  keep_.resize(n);
  const auto count = static_cast<std::int64_t>(n);
  const std::size_t wall_parts = drum.periodic() ? 1 : kWallParts;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    // Not `gap > reach`: a NaN gap keeps the part, so the wall loop sees it.
    std::uint8_t near = 0;
    for (std::size_t w = 0; w < wall_parts; ++w) {
      if (!(drum.part_gap(static_cast<WallPart>(w), p.position[i], p.radius[i]) > reach)) {
        near |= static_cast<std::uint8_t>(1u << w);
      } else {
        history[i][w].setZero();
      }
    }
    keep_[i] = near;
  }
  list_.reserve(n);  // once: later builds never allocate
  parts_.reserve(n);
  list_.clear();
  parts_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (keep_[i] == 0) continue;
    list_.push_back(static_cast<Index>(i));
    parts_.push_back(keep_[i]);
  }
  reference_.assign(p.position.begin(), p.position.end());
  reach_ = reach;
  moved_ = 0.0;
  ++rebuilds_;
  return true;
}

void WallCandidates::renumber(std::span<const Index> order, std::span<const Index> new_index) {
  if (reference_.size() != order.size()) {
    invalidate();
    return;
  }
  scratch_pairs_.resize(list_.size());
  for (std::size_t k = 0; k < list_.size(); ++k)
    scratch_pairs_[k] = {new_index[list_[k]], parts_[k]};
  std::sort(scratch_pairs_.begin(), scratch_pairs_.end());
  for (std::size_t k = 0; k < list_.size(); ++k) {
    list_[k] = scratch_pairs_[k].first;
    parts_[k] = scratch_pairs_[k].second;
  }
  apply_order(reference_, order, scratch_);
}

}  // namespace drumlab
