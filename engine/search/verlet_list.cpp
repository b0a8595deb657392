#include "engine/search/verlet_list.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "engine/search/search_input.hpp"

namespace drumlab {

VerletListSearch::VerletListSearch(std::unique_ptr<ContactSearch> builder, double skin_factor)
    : builder_(std::move(builder)), skin_factor_(skin_factor) {
  if (!(skin_factor > 0.0)) {
    throw InputError(fmt::format("verlet: skin factor must be positive, got {}", skin_factor));
  }
  name_ =
      builder_->name() == "m5" ? std::string("verlet") : fmt::format("verlet:{}", builder_->name());
  description_ =
      fmt::format("Verlet list, skin {} R_min, rebuilt by {} when a particle moved > skin/2",
                  skin_factor_, builder_->name());
}

bool VerletListSearch::needs_rebuild(const SearchInput& in) const {
  const std::size_t n = in.position.size();
  if (n != reference_.size() || in.margin != margin_ || in.period_z.value_or(0.0) != period_ ||
      !std::equal(radius_.begin(), radius_.end(), in.radius.begin())) {
    return true;
  }
  const double limit = 0.25 * skin_ * skin_;  // (skin / 2)^2
  for (std::size_t i = 0; i < n; ++i) {
    if (distance_squared(in.position[i], reference_[i], period_) > limit) return true;
  }
  return false;
}

void VerletListSearch::rebuild(const SearchInput& in) {
  const std::size_t n = in.position.size();
  const double rmin = n == 0 ? 0.0 : *std::min_element(in.radius.begin(), in.radius.end());
  skin_ = skin_factor_ * rmin;
  SearchInput wide = in;
  wide.margin = in.margin + skin_;
  builder_->find_pairs(wide, list_);
  // Sorted by (i, j), the filtered output is sorted too, which the contact list builds fastest.
  sort_pairs(list_, n, scratch_pairs_, scratch_counts_);
  reference_.assign(in.position.begin(), in.position.end());
  radius_.assign(in.radius.begin(), in.radius.end());
  margin_ = in.margin;
  period_ = in.period_z.value_or(0.0);
  ++rebuilds_;
}

void VerletListSearch::find_pairs(const SearchInput& in, std::vector<IndexPair>& out) {
  validate_search_input(in);
  ++calls_;
  const bool rebuilt = needs_rebuild(in);
  if (rebuilt) rebuild(in);
  const std::size_t n = in.position.size();
  reset_counters(n);
  if (rebuilt) {
    counters_ = builder_->counters();
    std::copy(builder_->cells_visited_per_particle().begin(),
              builder_->cells_visited_per_particle().end(), cells_per_particle_.begin());
    std::copy(builder_->pairs_tested_per_particle().begin(),
              builder_->pairs_tested_per_particle().end(), tests_per_particle_.begin());
  }
  out.clear();
  const double margin = in.margin + kTouchTolerance;
  for (const IndexPair& p : list_) {
    const double cut = in.radius[p.i] + in.radius[p.j] + margin;
    if (distance_squared(in.position[p.i], in.position[p.j], period_) <= cut * cut)
      out.push_back(p);
    ++tests_per_particle_[p.i];
  }
  counters_.pairs_tested += list_.size();
  counters_.pairs_found = out.size();
}

std::string VerletListSearch::report() const {
  const double n = std::max<double>(1.0, static_cast<double>(reference_.size()));
  return fmt::format(
      "Verlet list: {} rebuilds in {} calls (every {:.1f} calls), {:.2f} listed pairs/particle",
      rebuilds_, calls_,
      rebuilds_ > 0 ? static_cast<double>(calls_) / static_cast<double>(rebuilds_) : 0.0,
      static_cast<double>(list_.size()) / n);
}

}  // namespace drumlab
