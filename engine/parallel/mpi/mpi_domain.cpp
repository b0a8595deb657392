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
#include "engine/parallel/mpi/global_order.hpp"
#include "engine/parallel/mpi/rcb_mpi.hpp"
#include "engine/parallel/start_message.hpp"
#include "engine/periodic.hpp"
#include "engine/spatial_order.hpp"

namespace drumlab {

namespace {

/// Whether a and b hold the same extra arrays (names, in order).
bool same_arrays(const Particles& a, const Particles& b) {
  if (a.extra.size() != b.extra.size()) return false;
  for (std::size_t k = 0; k < a.extra.size(); ++k) {
    if (a.extra[k].name != b.extra[k].name) return false;
  }
  return true;
}

/// Owned particles, sorted by serial slot.
struct OwnedSet {
  Particles p;
  WallHistory wall;
  std::vector<std::uint64_t> slot;
};

/// The `count` records packed in `bytes`, sorted by serial slot.
std::vector<PackedPiece> sorted_pieces(std::span<const std::byte> bytes, std::size_t count,
                                       std::size_t size) {
  std::vector<PackedPiece> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::byte* at = bytes.data() + k * size;
    out[k] = {packed_slot({at, size}), at, -1};
  }
  std::sort(out.begin(), out.end(),
            [](const PackedPiece& a, const PackedPiece& b) { return a.slot < b.slot; });
  return out;
}

/// Unpacks `count` particles from `bytes` in the order of their serial slots.
OwnedSet unpack_owned(const Particles& like, std::span<const std::byte> bytes, std::size_t count) {
  const std::size_t size = packed_size(like);
  OwnedSet o{empty_like(like), {}, {}};
  o.p.reserve(count);
  for (const PackedPiece& piece : sorted_pieces(bytes, count, size)) {
    std::size_t pos = 0;
    o.slot.push_back(unpack_particle({piece.at, size}, pos, o.p, o.wall));
  }
  return o;
}

/// A section of a message: a count, then that many packed items.
void put_count(std::vector<std::byte>& out, std::size_t n) {
  put_bytes(out, static_cast<std::uint64_t>(n));
}

/// Reads a message of two sections (particles, then contact records): appends the particles'
/// bytes to `owned` and the records to `records`; returns the particle count.
std::size_t read_message(std::span<const std::byte> msg, const Particles& like,
                         std::vector<std::byte>& owned, ContactRecords& records) {
  std::size_t pos = 0;
  const auto n = get_bytes<std::uint64_t>(msg, pos);
  const std::size_t begin = pos;
  pos += static_cast<std::size_t>(n) * packed_size(like);
  owned.insert(owned.end(), msg.begin() + static_cast<std::ptrdiff_t>(begin),
               msg.begin() + static_cast<std::ptrdiff_t>(pos));
  const auto m = get_bytes<std::uint64_t>(msg, pos);
  for (std::uint64_t k = 0; k < m; ++k) records.unpack(msg, pos);
  return static_cast<std::size_t>(n);
}

}  // namespace

MpiDomain::MpiDomain(MPI_Comm comm, MpiDomainOptions options)
    : comm_(comm), options_(std::move(options)) {
  const auto r = static_cast<std::size_t>(comm_.size());
  send_.assign(r, {});
  recv_.assign(r, {});
  send_buf_.assign(r, {});
  recv_buf_.assign(r, {});
}

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

std::unique_ptr<Simulation> MpiDomain::distribute(const SceneConfig& scene,
                                                  std::optional<SimulationState> full) {
  // Rank 0 cuts the whole state and sends every other rank its part, one rank after the other (it
  // holds the state and one packed part at a time); no other rank ever holds more than its part.
  std::vector<std::byte> header;
  StartPart part;
  if (comm_.rank() == 0) {
    if (!full) throw std::logic_error("MpiDomain::distribute: no state on rank 0");
    const std::span<const Vec3> x = full->particles.position;
    const Decomposition d = rcb_decompose(x, {}, options_.domain, comm_.size());
    header = pack_start_header(*full, d);
    comm_.broadcast(header);
    const GhostLayer g =
        ghost_layer(d, x, full->particles.radius, options_.reach, options_.period_z);
    std::vector<std::uint8_t> held(x.size(), 0);
    for (int q = 1; q < comm_.size(); ++q) {
      const StartPart p = start_part(*full, d, g, q, held);
      const auto count = static_cast<std::uint64_t>(p.owned_count);
      comm_.send(q, std::as_bytes(std::span(&count, 1)));
      comm_.send(q, p.owned);
      for (const auto& ghosts : p.ghosts) comm_.send(q, ghosts);
      comm_.send(q, pack_records(p.records));
    }
    part = start_part(*full, d, g, 0, held);
    full.reset();  // before this rank builds its own local set
  } else {
    comm_.broadcast(header);
    const std::vector<std::byte> count = comm_.receive(0);
    std::uint64_t n = 0;
    std::memcpy(&n, count.data(), sizeof n);
    part.owned_count = static_cast<std::size_t>(n);
    part.owned = comm_.receive(0);
    part.ghosts.resize(static_cast<std::size_t>(comm_.size()));
    for (auto& ghosts : part.ghosts) ghosts = comm_.receive(0);
    part.records = unpack_records(comm_.receive(0));
  }
  StartHeader h = unpack_start_header(header);
  decomposition_ = std::move(h.decomposition);
  particles_ = h.particles;
  cell_ = 2.0 * h.max_radius;
  return start_local(scene, std::move(h.state), std::move(part));
}

std::unique_ptr<Simulation> MpiDomain::distribute_shares(const SceneConfig& scene,
                                                         SimulationState share, std::uint64_t first,
                                                         std::uint64_t total) {
  const Particles& p = share.particles;
  decomposition_ = rcb_decompose_mpi(comm_, p.position, {}, options_.domain);
  particles_ = total;
  cell_ = 2.0 * comm_.max(p.size() > 0 ? p.max_radius() : 0.0);
  // Where each particle of the share goes: its owner first, then the ranks holding it as a ghost.
  std::vector<std::size_t> at(p.size() + 1, 0);
  std::vector<int> dest, near;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int owner = decomposition_.owner[i];
    dest.push_back(owner);
    ranks_within(decomposition_, p.position[i], options_.reach.of(p.radius[i]), options_.period_z,
                 near);
    for (const int q : near) {
      if (q != owner) dest.push_back(q);
    }
    at[i + 1] = dest.size();
  }
  // The share's contact records (keyed by slot), its contact arrays freed.
  ContactRecords rows;  // record e is the share's contact e
  rows.state_size = share.contact_state_size;
  std::vector<std::size_t> row_at = std::move(share.contact_row_start);
  if (row_at.empty()) row_at.assign(p.size() + 1, 0);  // a list never built: no rows
  for (std::size_t i = 0; i + 1 < row_at.size(); ++i) {
    for (std::size_t e = row_at[i]; e < row_at[i + 1]; ++e) {
      rows.add(first + i, share.contact_col[e], share.contact_history[e],
               std::span(share.contact_state).subspan(e * rows.state_size, rows.state_size));
    }
  }
  share.contact_col = {};
  share.contact_history = {};
  share.contact_state = {};
  // One message per rank, built and exchanged in turn (in round k a rank sends to rank + k and
  // receives from rank - k), so that a rank holds its share, one message and its part: to each
  // rank the particles it owns, those it holds as ghosts, and the records of the rows of the
  // particles it holds (it keeps those whose partner it holds too).
  const int ranks = comm_.size();
  const std::size_t size = packed_size(p);
  StartPart part;
  part.ghosts.assign(static_cast<std::size_t>(ranks), {});
  part.records.state_size = rows.state_size;
  for (int k = 0; k < ranks; ++k) {
    const int to = (comm_.rank() + k) % ranks, from = (comm_.rank() - k + ranks) % ranks;
    std::vector<std::byte> owned, ghosts, recs;
    std::uint64_t counts[3] = {0, 0, 0};
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto d = std::span(dest).subspan(at[i], at[i + 1] - at[i]);
      if (std::find(d.begin(), d.end(), to) == d.end()) continue;
      pack_particle(p, i, first + i, share.wall_history[i], d.front() == to ? owned : ghosts);
      ++counts[d.front() == to ? 0 : 1];
      for (std::size_t e = row_at[i]; e < row_at[i + 1]; ++e) {
        rows.pack(e, recs);
        ++counts[2];
      }
    }
    std::vector<std::byte> msg;
    msg.reserve(3 * sizeof(std::uint64_t) + owned.size() + ghosts.size() + recs.size());
    for (const auto& [count, bytes] : {std::pair{counts[0], &owned}, std::pair{counts[1], &ghosts},
                                       std::pair{counts[2], &recs}}) {
      put_count(msg, count);
      msg.insert(msg.end(), bytes->begin(), bytes->end());
    }
    owned = ghosts = recs = {};
    const std::vector<std::byte> got = k == 0 ? std::move(msg) : comm_.send_receive(to, msg, from);
    std::size_t pos = 0;
    const auto n_owned = get_bytes<std::uint64_t>(got, pos);
    part.owned.insert(part.owned.end(), got.begin() + static_cast<std::ptrdiff_t>(pos),
                      got.begin() + static_cast<std::ptrdiff_t>(pos + n_owned * size));
    part.owned_count += static_cast<std::size_t>(n_owned);
    pos += n_owned * size;
    const auto n_ghosts = get_bytes<std::uint64_t>(got, pos);
    for (std::uint64_t g = 0; g < n_ghosts; ++g, pos += size) {
      const std::span<const std::byte> record(got.data() + pos, size);
      auto& to_owner =
          part.ghosts[static_cast<std::size_t>(rcb_owner(decomposition_, packed_position(record)))];
      to_owner.insert(to_owner.end(), record.begin(), record.end());
    }
    const auto n_records = get_bytes<std::uint64_t>(got, pos);
    for (std::uint64_t r = 0; r < n_records; ++r) part.records.unpack(got, pos);
  }
  rows = {};  // freed before the local set is built
  row_at = {};
  dest = {};
  at = {};
  // Each owner's ghosts in ascending slot, the order in which it sends their motion.
  for (auto& g : part.ghosts) {
    std::vector<std::byte> sorted;
    sorted.reserve(g.size());
    for (const PackedPiece& piece : sorted_pieces(g, g.size() / size, size)) {
      sorted.insert(sorted.end(), piece.at, piece.at + size);
    }
    g = std::move(sorted);
  }
  SimulationState scalars;  // the share's scalars, with its extra arrays registered
  scalars.particles = empty_like(p);
  scalars.time = share.time;
  scalars.dt = share.dt;
  scalars.drum_omega = share.drum_omega;
  scalars.drum_angle = share.drum_angle;
  scalars.steps = share.steps;
  scalars.search_method = share.search_method;
  scalars.contact_state_size = share.contact_state_size;
  share = {};
  return start_local(scene, std::move(scalars), std::move(part));
}

std::unique_ptr<Simulation> MpiDomain::start_local(const SceneConfig& scene,
                                                   SimulationState scalars, StartPart part) {
  last_balance_ = scalars.steps;
  window_wall_ = MPI_Wtime();
  window_comm_ = comm_.seconds();
  // A Simulation over the owned particles (the scalars and search method given); assemble then
  // gives it the ghosts and the contact list.
  SimulationState start = std::move(scalars);
  const std::size_t size = packed_size(start.particles);
  OwnedSet o = unpack_owned(start.particles, part.owned, part.owned_count);
  start.particles = std::move(o.p);
  start.wall_history = std::move(o.wall);
  // A rank's part may hold what another rank's does not (a radius or a position the Simulation
  // refuses): the first rank to refuse its part speaks for all, before any rank waits for the
  // others again.
  std::unique_ptr<Simulation> sim;
  comm_.agree([&] { sim = std::make_unique<Simulation>(scene, std::move(start)); });
  assemble(*sim, sorted_pieces(part.owned, part.owned_count, size), part.ghosts,
           std::move(part.records), false);
  events_.set_ghosts(&sim->ghost_mask());
  sim->set_domain(this);
  return sim;
}

void MpiDomain::refresh_ghosts(Simulation& sim, double moved) {
  // One rank has no ghosts and nothing to migrate: its Simulation is the serial one.
  if (comm_.size() == 1) return;
  // `moved` is already every rank's bound: all ranks take the same branch.
  moved_ += moved;
  // The bound only grows; once it passes half the skin, the real displacements decide (one more
  // reduction), as the serial Verlet list checks its particles only when its bound says so. A
  // pair (owned, not here) was more than the reach, cut-off plus skin, apart at the exchange: it
  // can interact only once the two largest displacements sum to more than the skin.
  bool due = !(2.0 * moved_ <= options_.skin);
  if (due) {
    const auto [first, second] = measured_displacement(sim);
    due = !(first + second <= options_.skin);
    moved_ = first;
  }
  const bool rebalance_due = options_.rebalance_every > 0 &&
                             sim.steps() + 1 - last_balance_ >= options_.rebalance_every &&
                             balance_check(sim);
  if (due || rebalance_due) {
    if (rebalance_due) rebalance(sim);
    exchange(sim);
  } else {
    forward(sim);
  }
}

std::pair<double, double> MpiDomain::measured_displacement(const Simulation& sim) {
  const Particles& p = sim.particles();
  const double period = options_.period_z.value_or(0.0);
  double top[2] = {0.0, 0.0};  // the two largest squared displacements here
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (sim.is_ghost(i)) continue;
    const double d2 = nearest_image(p.position[i], reference_[i], period).squaredNorm();
    if (!(d2 <= top[1])) {  // NaN: an infinite displacement
      top[1] = std::isnan(d2) ? std::numeric_limits<double>::infinity() : d2;
      if (top[1] > top[0]) std::swap(top[0], top[1]);
    }
  }
  const std::vector<double> all = comm_.all_gather(std::span<const double>(top, 2));
  std::vector<double> sorted(all);
  std::partial_sort(sorted.begin(), sorted.begin() + 2, sorted.end(), std::greater<>());
  return {std::sqrt(sorted[0]), std::sqrt(sorted[1])};
}

void MpiDomain::forward(Simulation& sim) {
  Particles& p = sim.local_particles();
  for (std::size_t q = 0; q < send_.size(); ++q) {
    // 72 bytes a ghost into a buffer that keeps its size between exchanges.
    send_buf_[q].resize(9 * send_[q].size());
    double* b = send_buf_[q].data();
    for (const Index i : send_[q]) {
      std::memcpy(b, p.position[i].data(), 3 * sizeof(double));
      std::memcpy(b + 3, p.velocity[i].data(), 3 * sizeof(double));
      std::memcpy(b + 6, p.omega[i].data(), 3 * sizeof(double));
      b += 9;
    }
    recv_buf_[q].resize(9 * recv_[q].size());
  }
  comm_.exchange(send_buf_, recv_buf_);
  for (std::size_t q = 0; q < recv_.size(); ++q) {
    const double* b = recv_buf_[q].data();
    for (const Index i : recv_[q]) {
      p.position[i] = Vec3(b[0], b[1], b[2]);
      p.velocity[i] = Vec3(b[3], b[4], b[5]);
      p.omega[i] = Vec3(b[6], b[7], b[8]);
      b += 9;
    }
  }
}

void MpiDomain::copy_to_ghosts(std::span<std::uint64_t> values) {
  if (values.size() != slot_.size()) {
    throw std::logic_error("copy_to_ghosts: not one value per local particle");
  }
  std::vector<std::vector<std::uint64_t>> out(send_.size()), in(recv_.size());
  for (std::size_t q = 0; q < send_.size(); ++q) {
    for (const Index i : send_[q]) out[q].push_back(values[i]);
    in[q].resize(recv_[q].size());
  }
  comm_.exchange(out, in);
  for (std::size_t q = 0; q < recv_.size(); ++q) {
    for (std::size_t k = 0; k < recv_[q].size(); ++k) values[recv_[q][k]] = in[q][k];
  }
}

bool MpiDomain::balance_check(const Simulation& sim) {
  last_balance_ = sim.steps() + 1;
  // This rank's work in the window: its wall time outside MPI (the waits for slower ranks are
  // inside), taken before the gather below adds its own wait.
  const double work = (MPI_Wtime() - window_wall_) - (comm_.seconds() - window_comm_);
  std::uint64_t owned = 0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) owned += sim.is_ghost(i) ? 0 : 1;
  const std::vector<double> all = comm_.all_gather(std::span<const double>(&work, 1));
  window_wall_ = MPI_Wtime();
  window_comm_ = comm_.seconds();
  if (options_.balance == BalanceBy::count) return true;
  const double mean = std::accumulate(all.begin(), all.end(), 0.0) / double(all.size());
  const double imbalance = mean > 0.0 ? *std::max_element(all.begin(), all.end()) / mean : 1.0;
  if (first_imbalance_ == 0.0) first_imbalance_ = imbalance;
  last_imbalance_ = imbalance;
  // Per particle; a rank that owns nothing (or measured nothing) weighs as the mean rank would.
  work_weight_ = owned > 0 && work > 0.0 ? work / double(owned) : 0.0;
  return options_.balance_threshold <= 0.0 || !(imbalance <= 1.0 + options_.balance_threshold);
}

void MpiDomain::rebalance(const Simulation& sim) {
  // The cuts from the owned particles where they are (rcb_decompose_mpi): no rank gathers them.
  const double start = MPI_Wtime();
  const Particles& p = sim.particles();
  std::vector<Vec3> x;
  x.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!sim.is_ghost(i)) x.push_back(p.position[i]);
  }
  std::vector<double> w;
  if (options_.balance == BalanceBy::time) {
    // A rank that measured nothing weighs its particles as the measured ones do on average.
    const bool measured = work_weight_ > 0.0;
    const double measured_weight = comm_.sum(measured ? work_weight_ * double(x.size()) : 0.0);
    const std::uint64_t measured_count = comm_.sum(std::uint64_t{measured ? x.size() : 0});
    const double fallback = measured_count > 0 ? measured_weight / double(measured_count) : 1.0;
    w.assign(x.size(), measured ? work_weight_ : fallback);
  }
  decomposition_ = rcb_decompose_mpi(comm_, x, w, options_.domain);
  ++rebalances_;
  recut_seconds_ += MPI_Wtime() - start;
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

void MpiDomain::reorder(Simulation& sim) {
  // The serial run's re-ordering (morton_order): cells of 2 r_max from the smallest coordinates of
  // all particles, ties by the current order.
  const Particles& p = sim.particles();
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (sim.is_ghost(i)) continue;
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p.position[i][k]);
  }
  comm_.min3(lo);
  const Vec3 origin(lo[0], lo[1], lo[2]);
  // Each owned particle's new serial slot is the rank of its (key, slot) among all ranks' owned
  // ones (a sample sort over the ranks); each ghost's comes from its owner.
  std::vector<OrderKey> mine;
  mine.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!sim.is_ghost(i)) mine.push_back({morton_key(p.position[i], origin, cell_), slot_[i]});
  }
  const std::vector<std::uint64_t> ranked = global_ranks(comm_, mine);
  std::vector<std::uint64_t> next(p.size());
  for (std::size_t i = 0, k = 0; i < p.size(); ++i) {
    if (!sim.is_ghost(i)) next[i] = ranked[k++];
  }
  copy_to_ghosts(next);
  std::vector<Index> order(p.size()), new_index(p.size());
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return next[a] < next[b]; });
  for (std::size_t k = 0; k < order.size(); ++k) {
    new_index[order[k]] = static_cast<Index>(k);
    slot_[k] = next[order[k]];
  }
  sim.permute_particles(order, slot_);
  std::vector<Vec3> scratch;
  apply_order(reference_, order, scratch);
  for (auto* lists : {&send_, &recv_}) {
    for (auto& list : *lists) {
      for (Index& i : list) i = new_index[i];
    }
  }
}

std::optional<SimulationState> MpiDomain::gather(const Simulation& sim) {
  const SimulationState local = sim.state();
  const auto& ghost = sim.ghost_mask();
  std::vector<std::byte> parts, recs;
  std::size_t count = 0;
  for (std::size_t i = 0; i < local.particles.size(); ++i) {
    if (ghost[i] != 0) continue;
    pack_particle(local.particles, i, slot_[i], local.wall_history[i], parts);
    ++count;
  }
  ContactRecords records;  // each pair once: on the owner of its first particle
  collect_records(
      local, slot_, [&](std::size_t i, std::size_t) { return ghost[i] == 0; }, records);
  std::vector<std::byte> msg;
  put_count(msg, count);
  msg.insert(msg.end(), parts.begin(), parts.end());
  put_count(msg, records.size());
  for (std::size_t k = 0; k < records.size(); ++k) records.pack(k, msg);
  const auto in = comm_.gather(msg);
  if (comm_.rank() != 0) return std::nullopt;
  std::vector<std::byte> owned;
  std::size_t owned_count = 0;
  ContactRecords all;
  all.state_size = records.state_size;
  for (const auto& m : in) owned_count += read_message(m, local.particles, owned, all);
  OwnedSet o = unpack_owned(local.particles, owned, owned_count);
  SimulationState s = local;
  s.particles = std::move(o.p);
  s.wall_history = std::move(o.wall);
  assign_records(
      std::move(all), o.slot, [](std::size_t, std::size_t) { return true; }, s);
  return s;
}

MpiBalance MpiDomain::balance(const Simulation& sim) {
  std::uint64_t owned = 0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) owned += sim.is_ghost(i) ? 0 : 1;
  const std::vector<std::uint64_t> all = comm_.all_gather(std::span(&owned, 1));
  MpiBalance b;
  b.owned_min = *std::min_element(all.begin(), all.end());
  b.owned_max = *std::max_element(all.begin(), all.end());
  b.owned_mean = static_cast<double>(std::accumulate(all.begin(), all.end(), std::uint64_t{0})) /
                 static_cast<double>(all.size());
  b.exchanges = exchanges_;
  b.rebalances = rebalances_;
  b.first_imbalance = first_imbalance_;
  b.last_imbalance = last_imbalance_;
  b.ghosts_new = comm_.sum(ghosts_new_);
  b.ghosts_kept = comm_.sum(ghosts_kept_);
  b.bridge_events = events_.replayed();
  b.comm_seconds = comm_.seconds();
  b.exchange_seconds = exchange_seconds_;
  b.recut_seconds = recut_seconds_;
  return b;
}

}  // namespace drumlab
