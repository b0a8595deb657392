// MpiDomain's exchanges: particles migrate to the rank whose box holds them, the ghost layer is
// rebuilt (new ghosts in full, kept ghosts their motion only), and the next local set is
// assembled in the serial order.
#include "engine/parallel/mpi/mpi_domain.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "engine/parallel/ghost_layer.hpp"
#include "engine/parallel/local_set.hpp"
#include "engine/parallel/mpi/domain_messages.hpp"
#include "engine/parallel/mpi/global_order.hpp"
#include "engine/parallel/mpi/rcb_mpi.hpp"
#include "engine/parallel/start_message.hpp"
#include "engine/periodic.hpp"
#include "engine/spatial_order.hpp"

namespace drumlab {

using namespace domain_messages;

std::vector<std::vector<std::byte>> MpiDomain::ghost_packs(
    std::span<const PackedPiece> owned, const Simulation& sim,
    const std::vector<std::vector<std::uint64_t>>& sent) {
  const Particles& p = sim.particles();
  const std::size_t size = packed_size(p);
  const auto r = static_cast<std::size_t>(comm_.size());
  std::vector<std::vector<std::byte>> full(r), motion(r);
  std::vector<std::vector<Index>> kept(r);
  for (auto& s : send_) s.clear();
  std::vector<int> near;
  for (std::size_t k = 0; k < owned.size(); ++k) {
    const PackedPiece& e = owned[k];
    const Vec3 x = e.at != nullptr ? packed_position({e.at, size}) : p.position[e.local];
    const double r = e.at != nullptr ? packed_radius({e.at, size}) : p.radius[e.local];
    ranks_within(decomposition_, x, options_.reach.of(r), options_.period_z, near);
    for (const int q : near) {
      if (q == comm_.rank()) continue;
      const auto uq = static_cast<std::size_t>(q);
      // Owned-set indices, made local in assemble.
      if (!sent.empty() && std::binary_search(sent[uq].begin(), sent[uq].end(), e.slot)) {
        put_bytes(motion[uq], e.slot);  // q holds it as a ghost already: its motion only
        if (e.at != nullptr) {
          motion[uq].insert(motion[uq].end(), e.at, e.at + kPackedMotionBytes);
        } else {
          put_bytes(motion[uq], p.position[e.local]);
          put_bytes(motion[uq], p.velocity[e.local]);
          put_bytes(motion[uq], p.omega[e.local]);
        }
        kept[uq].push_back(static_cast<Index>(k));
      } else {
        if (e.at != nullptr) {
          full[uq].insert(full[uq].end(), e.at, e.at + size);
        } else {
          pack_particle(p, e.local, e.slot, sim.wall_history()[e.local], full[uq]);
        }
        send_[uq].push_back(static_cast<Index>(k));
      }
    }
  }
  // To q: the count of new ghosts, their records, then the kept ghosts' slots and motion.
  std::vector<std::vector<std::byte>> out(r);
  for (std::size_t q = 0; q < r; ++q) {
    put_count(out[q], send_[q].size());
    out[q].insert(out[q].end(), full[q].begin(), full[q].end());
    out[q].insert(out[q].end(), motion[q].begin(), motion[q].end());
    if (!sent.empty()) {
      ghosts_new_ += send_[q].size();
      ghosts_kept_ += kept[q].size();
    }
    send_[q].insert(send_[q].end(), kept[q].begin(), kept[q].end());
  }
  return out;
}

void MpiDomain::received_ghosts(const std::vector<std::vector<std::byte>>& in, std::size_t size,
                                std::vector<PackedPiece>& ghosts) const {
  for (std::size_t q = 0; q < in.size(); ++q) {
    const std::vector<std::byte>& msg = in[q];
    std::size_t pos = 0;
    const auto n = get_bytes<std::uint64_t>(msg, pos);
    for (std::uint64_t m = 0; m < n; ++m, pos += size) {
      ghosts.push_back(
          {packed_slot({msg.data() + pos, size}), msg.data() + pos, static_cast<int>(q)});
    }
    while (pos < msg.size()) {  // kept: our copy (slot_ still holds the current slots), new motion
      const auto slot = get_bytes<std::uint64_t>(msg, pos);
      const auto it = std::lower_bound(slot_.begin(), slot_.end(), slot);
      if (it == slot_.end() || *it != slot) {
        throw std::logic_error("MpiDomain: a kept ghost that this rank does not hold");
      }
      const auto i = static_cast<Index>(it - slot_.begin());
      ghosts.push_back({slot, nullptr, static_cast<int>(q), i, msg.data() + pos});
      pos += kPackedMotionBytes;
    }
  }
}

void MpiDomain::assemble(Simulation& sim, std::vector<PackedPiece> owned,
                         const std::vector<std::vector<std::byte>>& given, ContactRecords records,
                         bool migration) {
  const Particles& like = sim.particles();
  const std::size_t size = packed_size(like);
  // The ghosts each rank holds of ours (serial slots, ascending): they get their motion only.
  std::vector<std::vector<std::uint64_t>> sent(migration ? send_.size() : 0);
  for (std::size_t q = 0; q < sent.size(); ++q) {
    for (const Index i : send_[q]) sent[q].push_back(slot_[i]);
    std::sort(sent[q].begin(), sent[q].end());
  }
  // Ghosts for the others first (send_ in owned-set indices), then ours from them, in message
  // order (recv_ lists them so).
  const auto out = ghost_packs(owned, sim, sent);
  std::vector<std::vector<std::byte>> in;  // the ghosts' pieces point into it
  std::vector<PackedPiece> ghosts;
  if (migration) {
    in = comm_.all_to_all(out);
    received_ghosts(in, size, ghosts);
  } else {
    for (std::size_t q = 0; q < given.size(); ++q) {
      for (std::size_t pos = 0; pos < given[q].size(); pos += size) {
        const std::byte* at = given[q].data() + pos;
        ghosts.push_back({packed_slot({at, size}), at, static_cast<int>(q)});
      }
    }
  }
  // The next local set in serial order: the owned (sorted) merged with the sorted ghosts.
  std::vector<Index> by_slot(ghosts.size());
  std::iota(by_slot.begin(), by_slot.end(), Index{0});
  std::sort(by_slot.begin(), by_slot.end(),
            [&](Index a, Index b) { return ghosts[a].slot < ghosts[b].slot; });
  const std::size_t n = owned.size() + ghosts.size();
  std::vector<const PackedPiece*> seq;
  seq.reserve(n);
  std::vector<std::uint8_t> ghost(n, 0);
  std::vector<Index> owned_at(owned.size()), ghost_at(ghosts.size());
  std::vector<std::uint64_t> next_slot;
  next_slot.reserve(n);
  for (std::size_t a = 0, b = 0; a < owned.size() || b < by_slot.size();) {
    const auto local = static_cast<Index>(seq.size());
    if (b == by_slot.size() || (a < owned.size() && owned[a].slot < ghosts[by_slot[b]].slot)) {
      owned_at[a] = local;
      seq.push_back(&owned[a++]);
    } else {
      ghost_at[by_slot[b]] = local;
      ghost[local] = 1;
      seq.push_back(&ghosts[by_slot[b++]]);
    }
    next_slot.push_back(seq.back()->slot);
  }
  SimulationState s;
  if (same_arrays(spare_.particles, like)) {  // last exchange's arrays, refilled
    s = std::move(spare_);
  } else {
    s.particles = empty_like(like);
  }
  fill_particles(seq, like, sim.wall_history(), size, s.particles, s.wall_history);
  if (migration) {
    // Each current particle's index in the next set by its slot, whatever its data came from
    // (n: not in it), for the contact list. Both sets are sorted by slot.
    std::vector<Index> new_of_old(like.size(), static_cast<Index>(n));
    for (std::size_t i = 0, k = 0; i < like.size(); ++i) {
      while (k < n && next_slot[k] < slot_[i]) ++k;
      if (k < n && next_slot[k] == slot_[i]) new_of_old[i] = static_cast<Index>(k);
    }
    merge_contacts(sim.contacts(), sim.ghost_mask(), new_of_old, ghost, next_slot, records, s);
  } else {
    assign_records(
        std::move(records), next_slot,
        [&](std::size_t i, std::size_t j) { return ghost[i] == 0 || ghost[j] == 0; }, s);
  }
  for (auto& list : send_) {
    for (Index& i : list) i = owned_at[i];
  }
  for (auto& r : recv_) r.clear();
  for (std::size_t g = 0; g < ghosts.size(); ++g) {  // in message order
    recv_[static_cast<std::size_t>(ghosts[g].source)].push_back(ghost_at[g]);
  }
  slot_ = std::move(next_slot);
  moved_ = 0.0;
  reference_ = s.particles.position;
  sim.replace_local(s, std::move(ghost), slot_);
  spare_ = std::move(s);
}

void MpiDomain::exchange(Simulation& sim) {
  // Only what moves is packed (the migrants here, the new ghosts in ghost_packs): the particles
  // that stay are copied from the current arrays into the next local set (assemble), their
  // contacts from the current list.
  const double start = MPI_Wtime();
  const Particles& p = sim.particles();
  const WallHistory& wall = sim.wall_history();
  const ContactList& c = sim.contacts();
  const auto& ghost = sim.ghost_mask();
  const std::size_t size = packed_size(p);
  const auto r = static_cast<std::size_t>(comm_.size());
  // Where each owned particle goes (-1: stays), and the migrants' bytes per destination.
  std::vector<int> dest(p.size(), -1);
  std::vector<std::vector<std::byte>> parts(r), recs(r);
  std::vector<std::size_t> migrants(r, 0), records_to(r, 0);
  std::vector<PackedPiece> staying;
  staying.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (ghost[i] != 0) continue;
    const int q = rcb_owner(decomposition_, p.position[i]);
    if (q == comm_.rank()) {
      staying.push_back({slot_[i], nullptr, -1, static_cast<Index>(i)});
      continue;
    }
    dest[i] = q;
    pack_particle(p, i, slot_[i], wall[i], parts[static_cast<std::size_t>(q)]);
    ++migrants[static_cast<std::size_t>(q)];
  }
  // The migrants' contact records, to each migrant's rank: the pairs with one particle owned
  // here. A listed pair whose history and state are all zero bits carries nothing: a pair new to
  // the rebuilt list starts with exactly that (ContactList::transfer_history), so it is left out.
  ContactRecords sending;
  sending.state_size = c.state_size();
  const auto row = c.row_start();
  const auto col = c.col();
  for (std::size_t i = 0; i < c.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const Index j = col[k];
      if (dest[i] < 0 && dest[j] < 0) continue;
      if ((ghost[i] != 0 && ghost[j] != 0) ||
          !carries_contact(c.history(), c.state(), sending.state_size, k)) {
        continue;
      }
      sending.add(slot_[i], slot_[j], c.history()[k],
                  c.state().subspan(k * sending.state_size, sending.state_size));
      for (const int q : {dest[i], dest[j] != dest[i] ? dest[j] : -1}) {
        if (q < 0) continue;
        sending.pack(sending.size() - 1, recs[static_cast<std::size_t>(q)]);
        ++records_to[static_cast<std::size_t>(q)];
      }
    }
  }
  std::vector<std::vector<std::byte>> out(r);
  for (std::size_t q = 0; q < r; ++q) {
    put_count(out[q], migrants[q]);
    out[q].insert(out[q].end(), parts[q].begin(), parts[q].end());
    put_count(out[q], records_to[q]);
    out[q].insert(out[q].end(), recs[q].begin(), recs[q].end());
  }
  const auto in = comm_.all_to_all(out);
  std::vector<std::byte>& arrived = owned_bytes_;
  arrived.clear();
  std::size_t arrived_count = 0;
  ContactRecords records;
  records.state_size = c.state_size();
  for (const auto& msg : in) {
    if (!msg.empty()) arrived_count += read_message(msg, p, arrived, records);
  }
  const std::vector<PackedPiece> arrivals = sorted_pieces(arrived, arrived_count, size);
  std::vector<PackedPiece> owned(staying.size() + arrivals.size());
  std::merge(staying.begin(), staying.end(), arrivals.begin(), arrivals.end(), owned.begin(),
             [](const PackedPiece& a, const PackedPiece& b) { return a.slot < b.slot; });
  assemble(sim, std::move(owned), {}, std::move(records), true);
  ++exchanges_;
  exchange_seconds_ += MPI_Wtime() - start;
}

}  // namespace drumlab
