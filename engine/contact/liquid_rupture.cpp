#include "engine/contact/liquid_rupture.hpp"

#include <algorithm>

namespace drumlab {

RuptureSharing::RuptureSharing(const CohesiveParts& parts, ContactList& contacts, double* film,
                               RuptureScratch& scratch)
    : contacts_(contacts), film_(film), scratch_(scratch) {
  const LiquidBridge* law = parts.get<LiquidBridge>();
  if (law == nullptr || !(law->rupture_to_bridges > 0.0) || film == nullptr) return;
  law_ = law;
  offset_ = parts.offset<LiquidBridge>();
}

void RuptureSharing::listed(std::size_t k, Index i, Index j, double gap) {
  double* s = &contacts_.state()[k * contacts_.state_size() + offset_];
  if (!(LiquidBridge::live(s) && law_->event(s, gap))) return;
  const double v = LiquidBridge::liquid(s);
  LiquidBridge::rupture(s, nullptr, i, j);  // emptied first: not one of its particles' others
  dropped(i, j, v);
}

void RuptureSharing::dropped(Index i, Index j, double v) {
  const double half = 0.5 * v;
  share(i, half);
  share(j, half);
}

void RuptureSharing::share(Index a, double half) {
  std::size_t n = 0;
  for_each_bridge(a, [&](double*) { ++n; });
  if (n == 0) {
    film_[a] += half;
    return;
  }
  const double to_bridges = law_->rupture_to_bridges * half;
  film_[a] += half - to_bridges;
  const double each = to_bridges / static_cast<double>(n);
  for_each_bridge(a, [&](double* s) { film_[a] += law_->add_shared(s, each); });
}

// f(state) for each live bridge of particle a, by increasing partner slot: the pairs (i, a) with
// i < a (the partner index), then row a.
template <class F>
void RuptureSharing::for_each_bridge(Index a, F&& f) {
  if (!indexed_) index();
  const auto row = contacts_.row_start();
  const std::size_t stride = contacts_.state_size();
  double* state = contacts_.state().data() + offset_;
  for (std::size_t q = scratch_.start[a]; q < scratch_.start[a + 1]; ++q) {
    double* s = state + scratch_.k[q] * stride;
    if (LiquidBridge::live(s)) f(s);
  }
  for (std::size_t k = row[a]; k < row[a + 1]; ++k) {
    double* s = state + k * stride;
    if (LiquidBridge::live(s)) f(s);
  }
}

// The transposed index of the list (scratch_.k by partner, then by row), built at the first
// rupture of a pass: the list does not change within it.
void RuptureSharing::index() {
  const std::size_t n = contacts_.rows();
  const auto row = contacts_.row_start();
  const auto col = contacts_.col();
  scratch_.start.assign(n + 1, 0);
  for (const Index j : col) ++scratch_.start[j + 1];
  for (std::size_t i = 0; i < n; ++i) scratch_.start[i + 1] += scratch_.start[i];
  scratch_.next.assign(scratch_.start.begin(), scratch_.start.end() - 1);
  scratch_.k.resize(col.size());
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) scratch_.k[scratch_.next[col[k]]++] = k;
  }
  indexed_ = true;
}

}  // namespace drumlab
