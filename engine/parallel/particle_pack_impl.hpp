#pragma once
// assign_records (engine/parallel/particle_pack.hpp).
#include <algorithm>
#include <numeric>

namespace drumlab {

template <class Keep>
void assign_records(ContactRecords r, std::span<const std::uint64_t> slot, Keep&& keep,
                    SimulationState& s) {
  const auto local = [&](std::uint64_t v) -> std::size_t {
    const auto it = std::lower_bound(slot.begin(), slot.end(), v);
    return it != slot.end() && *it == v ? static_cast<std::size_t>(it - slot.begin()) : slot.size();
  };
  struct Entry {
    std::size_t i, j, k;
  };
  std::vector<Entry> e;
  e.reserve(r.size());
  for (std::size_t k = 0; k < r.size(); ++k) {
    const std::size_t i = local(r.a[k]), j = local(r.b[k]);
    if (i < slot.size() && j < slot.size() && keep(i, j)) e.push_back({i, j, k});
  }
  std::sort(e.begin(), e.end(), [](const Entry& x, const Entry& y) {
    return x.i != y.i ? x.i < y.i : (x.j != y.j ? x.j < y.j : x.k < y.k);
  });
  e.erase(std::unique(e.begin(), e.end(),
                      [](const Entry& x, const Entry& y) { return x.i == y.i && x.j == y.j; }),
          e.end());
  const std::size_t n = slot.size(), m = e.size(), ss = r.state_size;
  s.contact_state_size = ss;
  s.contact_row_start.assign(n + 1, 0);
  s.contact_col.resize(m);
  s.contact_history.resize(m);
  s.contact_state.resize(m * ss);
  for (std::size_t q = 0; q < m; ++q) {
    ++s.contact_row_start[e[q].i + 1];
    s.contact_col[q] = static_cast<Index>(e[q].j);
    s.contact_history[q] = r.history[e[q].k];
    for (std::size_t c = 0; c < ss; ++c) s.contact_state[q * ss + c] = r.state[e[q].k * ss + c];
  }
  std::partial_sum(s.contact_row_start.begin(), s.contact_row_start.end(),
                   s.contact_row_start.begin());
}

}  // namespace drumlab
