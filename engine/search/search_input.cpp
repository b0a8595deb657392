#include "engine/search/search_input.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "engine/threads.hpp"

namespace drumlab {

void ContactSearch::reset_counters(std::size_t n) {
  counters_ = SearchCounters{};
  cells_per_particle_.assign(n, 0);
  tests_per_particle_.assign(n, 0);
}

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
  for (std::size_t i = 0; i < in.position.size(); ++i) {
    const Vec3& x = in.position[i];
    if (!x.allFinite())
      throw InputError(fmt::format("search: particle {} has a non-finite position", i));
    const double r = in.radius[i];
    if (!(r > 0.0) || !std::isfinite(r)) {
      throw InputError(fmt::format("search: particle {} has radius {} (must be positive)", i, r));
    }
    if (in.domain) {
      const Box& b = *in.domain;
      if ((x.array() < b.lo.array()).any() || (x.array() >= b.hi.array()).any()) {
        throw InputError(fmt::format("search: particle {} at ({}, {}, {}) lies outside the domain",
                                     i, x.x(), x.y(), x.z()));
      }
    }
    if (in.period_z && (x.z() < 0.0 || x.z() >= period)) {
      throw InputError(fmt::format("search: particle {} has z = {} outside the period [0, {})", i,
                                   x.z(), period));
    }
  }
}

void sort_pairs(std::vector<IndexPair>& pairs, std::size_t n, std::vector<IndexPair>& scratch,
                std::vector<std::uint32_t>& counts) {
  // Counting sort by i, each thread counting and placing a contiguous share of the pairs: with
  // counts per (row, thread) laid out by row, thread t's pairs of row i go after those of the
  // threads before it, so the rows come out in input order whatever the thread count.
  const std::size_t m = pairs.size();
  constexpr std::size_t kPairsPerThread = 32768;  // below this, one thread
  const int threads = static_cast<int>(
      std::clamp<std::size_t>(m / kPairsPerThread, 1, static_cast<std::size_t>(max_threads())));
  const auto t_count = static_cast<std::size_t>(threads);
  counts.assign(n * t_count + 1, 0);  // counts[i * T + t]; the last entry ends the last row
  scratch.resize(m);
#pragma omp parallel num_threads(threads)
  {
    const auto t = static_cast<std::size_t>(thread_number());
    const std::size_t begin = m * t / t_count;
    const std::size_t end = m * (t + 1) / t_count;
    for (std::size_t k = begin; k < end; ++k) ++counts[pairs[k].i * t_count + t];
#pragma omp barrier
#pragma omp single
    {
      std::uint32_t running = 0;
      for (std::uint32_t& c : counts) {
        const std::uint32_t here = c;
        c = running;
        running += here;
      }
    }
    for (std::size_t k = begin; k < end; ++k)
      scratch[counts[pairs[k].i * t_count + t]++] = pairs[k];
#pragma omp barrier
      // Row i now spans [end of row i - 1, counts[i * T + T - 1]); rows are short: insertion sort.
#pragma omp for schedule(static)
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
  }
  pairs.swap(scratch);
}

}  // namespace drumlab
