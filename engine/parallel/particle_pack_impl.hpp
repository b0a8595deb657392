#pragma once
// assign_records (engine/parallel/particle_pack.hpp).
#include <algorithm>
#include <numeric>
#include <vector>

namespace drumlab {

template <class Keep>
void assign_records(ContactRecords r, std::span<const std::uint64_t> slot, Keep&& keep,
                    SimulationState& s) {
  // The local slot of each serial slot in [slot.front(), slot.back()] (slot.size(): absent): two
  // look-ups a record without a search (4 bytes a serial slot in that range).
  const std::uint64_t lo = slot.empty() ? 0 : slot.front();
  std::vector<Index> table(slot.empty() ? 0 : slot.back() - lo + 1,
                           static_cast<Index>(slot.size()));
  for (std::size_t i = 0; i < slot.size(); ++i) table[slot[i] - lo] = static_cast<Index>(i);
  const auto local = [&](std::uint64_t v) -> std::size_t {
    return v >= lo && v - lo < table.size() ? table[v - lo] : slot.size();
  };
  struct Entry {
    std::size_t j, k;
  };
  // Bucketed by row (a counting sort), then each row sorted by partner and record.
  const std::size_t n = slot.size();
  std::vector<std::size_t> start(n + 1, 0);
  std::vector<std::size_t> row(r.size(), n), col(r.size(), n);
  for (std::size_t k = 0; k < r.size(); ++k) {
    const std::size_t i = local(r.a[k]), j = local(r.b[k]);
    if (i < n && j < n && keep(i, j)) {
      row[k] = i;
      col[k] = j;
      ++start[i + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<Entry> e(start[n]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (row[k] < n) e[fill[row[k]]++] = {col[k], k};
  }
  std::size_t m = 0;  // entries kept, duplicates (the same pair from two ranks) once
  for (std::size_t i = 0; i < n; ++i) {
    const auto first = e.begin() + static_cast<std::ptrdiff_t>(start[i]);
    const auto last = e.begin() + static_cast<std::ptrdiff_t>(start[i + 1]);
    std::sort(first, last,
              [](const Entry& x, const Entry& y) { return x.j != y.j ? x.j < y.j : x.k < y.k; });
    start[i] = m;
    for (auto it = first; it != last; ++it) {
      if (it == first || it->j != (it - 1)->j) e[m++] = *it;
    }
  }
  start[n] = m;
  e.resize(m);
  const std::size_t ss = r.state_size;
  s.contact_state_size = ss;
  s.contact_row_start.assign(start.begin(), start.end());
  s.contact_col.resize(m);
  s.contact_history.resize(m);
  s.contact_state.resize(m * ss);
  for (std::size_t q = 0; q < m; ++q) {
    s.contact_col[q] = static_cast<Index>(e[q].j);
    s.contact_history[q] = r.history[e[q].k];
    for (std::size_t c = 0; c < ss; ++c) s.contact_state[q * ss + c] = r.state[e[q].k * ss + c];
  }
}

}  // namespace drumlab
