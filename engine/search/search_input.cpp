#include "engine/search/search_input.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "engine/counting_sort.hpp"
#include "engine/parallel_copy.hpp"
#include "engine/threads.hpp"

namespace drumlab {

void ContactSearch::reset_counters(std::size_t n) {
  counters_ = SearchCounters{};
  parallel_fill<std::uint32_t>(cells_per_particle_, n, 0);
  parallel_fill<std::uint32_t>(tests_per_particle_, n, 0);
}

namespace {

/// What is wrong with particle i of a search's input, or nothing.
std::optional<std::string> particle_error(const SearchInput& in, std::size_t i, double period) {
  const Vec3& x = in.position[i];
  if (!x.allFinite()) return fmt::format("search: particle {} has a non-finite position", i);
  const double r = in.radius[i];
  if (!(r > 0.0) || !std::isfinite(r)) {
    return fmt::format("search: particle {} has radius {} (must be positive)", i, r);
  }
  if (in.domain) {
    const Box& b = *in.domain;
    if ((x.array() < b.lo.array()).any() || (x.array() >= b.hi.array()).any()) {
      return fmt::format("search: particle {} at ({}, {}, {}) lies outside the domain", i, x.x(),
                         x.y(), x.z());
    }
  }
  if (in.period_z && (x.z() < 0.0 || x.z() >= period)) {
    return fmt::format("search: particle {} has z = {} outside the period [0, {})", i, x.z(),
                       period);
  }
  return std::nullopt;
}

}  // namespace

void validate_search_input(const SearchInput& in) {
  if (in.position.size() != in.radius.size()) {
    throw InputError(
        fmt::format("search: {} positions but {} radii", in.position.size(), in.radius.size()));
  }
  if (!(in.margin >= 0.0) || !std::isfinite(in.margin)) {
    throw InputError(fmt::format("search: margin must be >= 0 and finite, got {}", in.margin));
  }
  const double period = in.period_z.value_or(0.0);
  if (in.period_z && !(period > 0.0 && std::isfinite(period))) {
    throw InputError(fmt::format("search: period_z must be positive, got {}", period));
  }
  // Every thread checks its share; the first particle at fault is reported, whatever the team.
  const auto n = static_cast<std::int64_t>(in.position.size());
  std::int64_t first = n;
#pragma omp parallel for schedule(static) reduction(min : first) if (n >= kParallelMinElements)
  for (std::int64_t i = 0; i < n; ++i) {
    if (i < first && particle_error(in, static_cast<std::size_t>(i), period)) first = i;
  }
  if (first < n) throw InputError(*particle_error(in, static_cast<std::size_t>(first), period));
}

void sort_pairs(std::vector<IndexPair>& pairs, std::size_t n, std::vector<IndexPair>& scratch,
                std::vector<std::uint32_t>& counts) {
  // Counting sort by i (counting_sort.hpp: the rows come out in input order whatever the thread
  // count), then each (short) row by j.
  const std::size_t m = pairs.size();
  constexpr std::size_t kPairsPerThread = 32768;  // below this, one thread
  scratch.resize(m);
  const std::size_t t_count = counting_sort_by_row(
      m, n, kPairsPerThread, counts, [&](std::size_t k) { return std::size_t{pairs[k].i}; },
      [&](std::size_t k, std::uint32_t slot) { scratch[slot] = pairs[k]; });
  // Row i now spans [end of row i - 1, counts[i * T + T - 1]); rows are short: insertion sort.
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const std::size_t row_begin = i == 0 ? 0 : counts[(i - 1) * t_count + t_count - 1];
    const std::size_t row_end = counts[i * t_count + t_count - 1];
    for (std::size_t a = row_begin + 1; a < row_end; ++a) {
      const IndexPair v = scratch[a];
      std::size_t b = a;
      for (; b > row_begin && scratch[b - 1].j > v.j; --b) scratch[b] = scratch[b - 1];
      scratch[b] = v;
    }
  }
  pairs.swap(scratch);
}

}  // namespace drumlab
