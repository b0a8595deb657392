#include "engine/search/brute_force.hpp"

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

}  // namespace drumlab
