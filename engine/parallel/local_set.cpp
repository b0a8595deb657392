#include "engine/parallel/local_set.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

namespace drumlab {

void fill_particles(std::span<const PackedPiece* const> seq, const Particles& p,
                    const WallHistory& wall, std::size_t size, Particles& out,
                    WallHistory& out_wall) {
  // Array by array (p and out visit the same arrays in the same order): each value copied from
  // its record at the array's offset there, or from the current array at the local index.
  std::vector<const void*> from;
  p.for_each_array([&](std::string_view, const auto& values) { from.push_back(values.data()); });
  const std::size_t n = seq.size();
  std::size_t a = 0, offset = 0;
  out.for_each_array([&](std::string_view, auto& values) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    const T* here = static_cast<const T*>(from[a++]);
    const bool motion = offset < kPackedMotionBytes;  // position, velocity, angular velocity
    values.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const PackedPiece& e = *seq[k];
      const std::byte* b = e.at != nullptr ? e.at : (motion ? e.motion : nullptr);
      if (b != nullptr) {
        std::memcpy(static_cast<void*>(&values[k]), b + offset, sizeof(T));
      } else {
        values[k] = here[e.local];
      }
    }
    offset += sizeof(T);
  });
  const std::size_t wall_at = size - kWallParts * sizeof(Vec3);
  out_wall.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const PackedPiece& e = *seq[k];
    if (e.at != nullptr) {
      std::memcpy(static_cast<void*>(&out_wall[k]), e.at + wall_at, kWallParts * sizeof(Vec3));
    } else {
      out_wall[k] = wall[e.local];
    }
  }
}

bool carries_contact(std::span<const Vec3> history, std::span<const double> state,
                     std::size_t state_size, std::size_t k) {
  const auto nonzero = [](const void* at, std::size_t bytes) {
    const auto* b = static_cast<const unsigned char*>(at);
    return std::any_of(b, b + bytes, [](unsigned char c) { return c != 0; });
  };
  return nonzero(&history[k], sizeof(Vec3)) ||
         (state_size > 0 && nonzero(&state[k * state_size], state_size * sizeof(double)));
}

void merge_contacts(const ContactList& old, std::span<const std::uint8_t> old_ghost,
                    std::span<const Index> new_of_old, std::span<const std::uint8_t> ghost,
                    std::span<const std::uint64_t> slot, const ContactRecords& records,
                    SimulationState& s) {
  const std::size_t n = ghost.size();
  const std::size_t ss = old.state_size();
  const auto row = old.row_start();
  const auto col = old.col();
  const auto history = old.history();
  const auto state = old.state();
  const auto local = [&](std::uint64_t v) -> std::size_t {
    const auto it = std::lower_bound(slot.begin(), slot.end(), v);
    return it != slot.end() && *it == v ? static_cast<std::size_t>(it - slot.begin()) : n;
  };
  // The records' entries in the next set, by (row, partner, record).
  struct Entry {
    std::size_t i, j, k;
  };
  std::vector<Entry> in;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const std::size_t i = local(records.a[k]), j = local(records.b[k]);
    if (i < n && j < n && (ghost[i] == 0 || ghost[j] == 0)) in.push_back({i, j, k});
  }
  std::sort(in.begin(), in.end(), [](const Entry& x, const Entry& y) {
    return x.i != y.i ? x.i < y.i : x.j != y.j ? x.j < y.j : x.k < y.k;
  });
  // Which old row becomes each new row (n: a particle new here).
  std::vector<std::size_t> old_of_new(n, old.rows());
  for (std::size_t i = 0; i < new_of_old.size(); ++i) {
    if (new_of_old[i] < n) old_of_new[new_of_old[i]] = i;
  }
  s.contact_state_size = ss;
  s.contact_row_start.assign(1, 0);
  s.contact_row_start.reserve(n + 1);
  s.contact_col.clear();
  s.contact_history.clear();
  s.contact_state.clear();
  s.contact_col.reserve(col.size() + in.size());
  s.contact_history.reserve(col.size() + in.size());
  s.contact_state.reserve((col.size() + in.size()) * ss);
  const auto put = [&](Index j, const Vec3& h, const double* st) {
    s.contact_col.push_back(j);
    s.contact_history.push_back(h);
    s.contact_state.insert(s.contact_state.end(), st, st + ss);
  };
  std::size_t e = 0;  // next record entry
  for (std::size_t i = 0; i < n; ++i) {
    // The old row's kept entries (their new partners increase: the renumbering keeps the order),
    // merged with the records of this row.
    const std::size_t io = old_of_new[i];
    std::size_t k = io < old.rows() ? row[io] : 0;
    const std::size_t k_end = io < old.rows() ? row[io + 1] : 0;
    const auto next_old = [&]() -> std::size_t {  // the next kept old entry, or k_end
      for (; k < k_end; ++k) {
        const Index jo = col[k];
        const Index j = new_of_old[jo];
        if (j >= n || (old_ghost[io] != 0 && old_ghost[jo] != 0)) continue;
        if (ghost[i] != 0 && ghost[j] != 0) continue;
        if (!carries_contact(history, state, ss, k)) continue;
        return k;
      }
      return k_end;
    };
    for (std::size_t ko = next_old(); ko < k_end || (e < in.size() && in[e].i == i);) {
      const bool have_old = ko < k_end;
      const bool have_rec = e < in.size() && in[e].i == i;
      const std::size_t jo = have_old ? new_of_old[col[ko]] : n;
      if (have_old && (!have_rec || jo <= in[e].j)) {
        put(static_cast<Index>(jo), history[ko], ss > 0 ? &state[ko * ss] : nullptr);
        while (e < in.size() && in[e].i == i && in[e].j == jo) ++e;  // the same pair, recorded
        ++k;
        ko = next_old();
      } else {
        const Entry& r = in[e];
        put(static_cast<Index>(r.j), records.history[r.k],
            ss > 0 ? &records.state[r.k * ss] : nullptr);
        while (e < in.size() && in[e].i == i && in[e].j == r.j) ++e;
      }
    }
    s.contact_row_start.push_back(s.contact_col.size());
  }
}

}  // namespace drumlab
