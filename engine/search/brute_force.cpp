#include "engine/search/brute_force.hpp"

#include <fmt/format.h>

#include "engine/search/search_input.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab {

std::string_view BruteForceSearch::description() const {
  return search_method(name()).description;
}

void BruteForceSearch::find_pairs(const SearchInput& in, std::vector<IndexPair>& out) {
  const auto t0 = SearchClock::now();
  validate_search_input(in);
  const std::size_t n = in.position.size();
  reset_counters(n);
  out.clear();
  const double period = in.period_z.value_or(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double cut = pair_cutoff(in.radius[i], in.radius[j], in.margin);
      if (distance_squared(in.position[i], in.position[j], period) <= cut * cut) {
        out.push_back({static_cast<Index>(i), static_cast<Index>(j)});
      }
    }
    tests_per_particle_[i] = static_cast<std::uint32_t>(n - i - 1);
  }
  counters_.pairs_tested = n < 2 ? 0 : n * (n - 1) / 2;
  counters_.pairs_found = out.size();
  timings_ = {0.0, seconds_since(t0)};
}

SearchVisit BruteForceSearch::visit(Index i, const SearchInput& in) const {
  validate_search_input(in);
  const std::size_t n = in.position.size();
  if (i >= n) throw InputError(fmt::format("visit: particle {} of {}", i, n));
  const double period = in.period_z.value_or(0.0);
  SearchVisit v;
  v.kind = SearchVisit::Kind::all;
  v.particle = i;
  for (std::size_t j = i + 1; j < n; ++j) {
    v.candidates.push_back(static_cast<Index>(j));
    const double cut = pair_cutoff(in.radius[i], in.radius[j], in.margin);
    if (distance_squared(in.position[i], in.position[j], period) <= cut * cut) {
      v.contacts.push_back(static_cast<Index>(j));
    }
  }
  v.pairs_tested = v.candidates.size();
  v.note = fmt::format(
      "brute force: no cells, tests all N-1 = {} pairs of it ({} by itself, the "
      "rest by the earlier particles)",
      n - 1, v.candidates.size());
  return v;
}

}  // namespace drumlab
