#pragma once
// The parallel counting sort by row behind the Verlet list's pair sort (search/search_input.cpp,
// sort_pairs) and the contact list's renumbering (contact/contact_history.cpp).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include "engine/threads.hpp"

namespace drumlab {

/// Sorts m items stably by their row (row_of(k) < n) in T contiguous shares (items
/// [m t / T, m (t + 1) / T) for share t of T): each share counts, then places its items, with the
/// counts laid out by (row, share), so every row keeps its items in input order whatever the
/// team. place(k, slot) is called once for each item with its place in the sorted order. The
/// shares go to the threads by number, not by thread: a team smaller than asked for (a nested
/// region, OMP_DYNAMIC) still counts and places every share. T is one share per
/// `items_per_share` items, at least 1 and at most the thread count. Returns T; on return
/// fill[i * T + T - 1] ends row i (fill holds n * T + 1 counts, then T values of scratch).
template <class Count, class RowOf, class Place>
std::size_t counting_sort_by_row(std::size_t m, std::size_t n, std::size_t items_per_share,
                                 std::vector<Count>& fill, RowOf&& row_of, Place&& place) {
  const std::size_t t_count =
      std::clamp<std::size_t>(m / items_per_share, 1, static_cast<std::size_t>(max_threads()));
  const auto share_count = static_cast<std::int64_t>(t_count);
  const int team = static_cast<int>(t_count);
  // The counts, then one sum per share for the scan (after the counts, where no row reads).
  const std::size_t counts = n * t_count + 1;
  fill.resize(counts + t_count);
  Count* piece_sum = fill.data() + counts;
  const auto count_size = static_cast<std::int64_t>(counts);
#pragma omp parallel num_threads(team)
  {
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < count_size; ++c) fill[static_cast<std::size_t>(c)] = Count{0};
#pragma omp for schedule(static)
    for (std::int64_t share = 0; share < share_count; ++share) {
      const auto t = static_cast<std::size_t>(share);
      for (std::size_t k = m * t / t_count; k < m * (t + 1) / t_count; ++k) {
        ++fill[row_of(k) * t_count + t];
      }
    }
    // The exclusive scan of the counts in t_count pieces: each piece's sum, the pieces' offsets
    // (one thread, t_count values), then each piece scanned from its offset. Integers: the same
    // result as one scan.
#pragma omp for schedule(static)
    for (std::int64_t share = 0; share < share_count; ++share) {
      const auto t = static_cast<std::size_t>(share);
      Count sum{0};
      for (std::size_t c = counts * t / t_count; c < counts * (t + 1) / t_count; ++c)
        sum += fill[c];
      piece_sum[t] = sum;
    }
#pragma omp single
    std::exclusive_scan(piece_sum, piece_sum + t_count, piece_sum, Count{0});
#pragma omp for schedule(static)
    for (std::int64_t share = 0; share < share_count; ++share) {
      const auto t = static_cast<std::size_t>(share);
      Count running = piece_sum[t];
      for (std::size_t c = counts * t / t_count; c < counts * (t + 1) / t_count; ++c) {
        const Count size = fill[c];
        fill[c] = running;
        running += size;
      }
    }
#pragma omp for schedule(static)
    for (std::int64_t share = 0; share < share_count; ++share) {
      const auto t = static_cast<std::size_t>(share);
      for (std::size_t k = m * t / t_count; k < m * (t + 1) / t_count; ++k) {
        place(k, fill[row_of(k) * t_count + t]++);
      }
    }
  }
  return t_count;
}

}  // namespace drumlab
