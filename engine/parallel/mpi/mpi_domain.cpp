#include "engine/parallel/mpi/mpi_domain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/parallel/ghost_layer.hpp"
#include "engine/periodic.hpp"
#include "engine/spatial_order.hpp"

namespace drumlab {

namespace {

/// Owned particles, sorted by serial slot.
struct OwnedSet {
  Particles p;
  WallHistory wall;
  std::vector<std::uint64_t> slot;
};

/// Unpacks `count` particles from `bytes` and sorts them by serial slot.
OwnedSet unpack_owned(const Particles& like, std::span<const std::byte> bytes, std::size_t count) {
  OwnedSet raw{empty_like(like), {}, {}};
  std::size_t pos = 0;
  for (std::size_t k = 0; k < count; ++k) {
    raw.slot.push_back(unpack_particle(bytes, pos, raw.p, raw.wall));
  }
  std::vector<Index> order(count);
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(),
            [&](Index a, Index b) { return raw.slot[a] < raw.slot[b]; });
  OwnedSet o{empty_like(like), {}, {}};
  std::vector<std::byte> one;
  for (const Index k : order) {
    one.clear();
    pack_particle(raw.p, k, raw.slot[k], raw.wall[k], one);
    std::size_t q = 0;
    o.slot.push_back(unpack_particle(one, q, o.p, o.wall));
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
  WallHistory w;
  Particles scratch = empty_like(like);  // walks the particles to find where they end
  for (std::uint64_t k = 0; k < n; ++k) unpack_particle(msg, pos, scratch, w);
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

std::vector<std::vector<std::byte>> MpiDomain::ghost_packs(const Particles& p,
                                                           const std::vector<std::uint64_t>& slot,
                                                           const WallHistory& wall) {
  const auto r = static_cast<std::size_t>(comm_.size());
  std::vector<std::vector<std::byte>> out(r);
  for (auto& s : send_) s.clear();
  std::vector<int> near;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ranks_within(decomposition_, p.position[i], options_.reach, options_.period_z, near);
    for (const int q : near) {
      if (q == comm_.rank()) continue;
      const auto uq = static_cast<std::size_t>(q);
      pack_particle(p, i, slot[i], wall[i], out[uq]);
      send_[uq].push_back(static_cast<Index>(i));  // owned-set index; made local in assemble
    }
  }
  return out;
}

void MpiDomain::assemble(Simulation& sim, const std::vector<std::byte>& owned,
                         std::size_t owned_count, const std::vector<std::vector<std::byte>>& ghosts,
                         ContactRecords records) {
  const Particles& like = sim.particles();
  OwnedSet o = unpack_owned(like, owned, owned_count);
  // Ghosts for the others first (send_ in owned-set indices), then ours from them.
  const auto out = ghost_packs(o.p, o.slot, o.wall);
  const auto in = ghosts.empty() ? comm_.all_to_all(out) : ghosts;
  OwnedSet g{empty_like(like), {}, {}};
  std::vector<int> source;
  for (std::size_t q = 0; q < in.size(); ++q) {
    std::size_t pos = 0;
    while (pos < in[q].size()) {
      g.slot.push_back(unpack_particle(in[q], pos, g.p, g.wall));
      source.push_back(static_cast<int>(q));
    }
  }
  // Merge by serial slot.
  const std::size_t n = o.slot.size() + g.slot.size();
  SimulationState s;
  s.particles = empty_like(like);
  std::vector<std::uint8_t> ghost(n, 0);
  std::vector<Index> owned_local(o.slot.size());
  for (auto& r : recv_) r.clear();
  slot_.clear();
  std::vector<std::byte> one;
  std::vector<Index> ghost_order(g.slot.size());
  std::iota(ghost_order.begin(), ghost_order.end(), Index{0});
  std::sort(ghost_order.begin(), ghost_order.end(),
            [&](Index a, Index b) { return g.slot[a] < g.slot[b]; });
  std::vector<Index> ghost_local(g.slot.size());
  std::size_t a = 0, b = 0;
  while (a < o.slot.size() || b < g.slot.size()) {
    const bool take_owned =
        b == g.slot.size() || (a < o.slot.size() && o.slot[a] < g.slot[ghost_order[b]]);
    const OwnedSet& from = take_owned ? o : g;
    const std::size_t k = take_owned ? a++ : ghost_order[b++];
    const auto local = static_cast<Index>(slot_.size());
    (take_owned ? owned_local[k] : ghost_local[k]) = local;
    ghost[local] = take_owned ? 0 : 1;
    one.clear();
    pack_particle(from.p, k, from.slot[k], from.wall[k], one);
    std::size_t pos = 0;
    slot_.push_back(unpack_particle(one, pos, s.particles, s.wall_history));
  }
  for (auto& list : send_) {
    for (Index& i : list) i = owned_local[i];
  }
  for (std::size_t k = 0; k < g.slot.size(); ++k) {
    recv_[static_cast<std::size_t>(source[k])].push_back(ghost_local[k]);
  }
  assign_records(
      std::move(records), slot_,
      [&](std::size_t i, std::size_t j) { return ghost[i] == 0 || ghost[j] == 0; }, s);
  moved_ = 0.0;
  reference_ = s.particles.position;
  sim.replace_local(std::move(s), std::move(ghost), slot_);
}

std::unique_ptr<Simulation> MpiDomain::distribute(const SceneConfig& scene,
                                                  const SimulationState& full) {
  const Particles& p = full.particles;
  cell_ = 2.0 * p.max_radius();
  decomposition_ = rcb_decompose(p.position, {}, options_.domain, comm_.size());
  last_balance_ = full.steps;
  const auto r = static_cast<std::size_t>(comm_.size());
  std::vector<std::byte> owned;
  std::size_t owned_count = 0;
  std::vector<std::vector<std::byte>> ghosts(r);
  const Box& mine = decomposition_.boxes[static_cast<std::size_t>(comm_.rank())];
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int owner = rcb_owner(decomposition_, p.position[i]);
    if (owner == comm_.rank()) {
      pack_particle(p, i, i, full.wall_history[i], owned);
      ++owned_count;
    } else if (box_distance(mine, p.position[i], options_.period_z) <= options_.reach) {
      pack_particle(p, i, i, full.wall_history[i], ghosts[static_cast<std::size_t>(owner)]);
    }
  }
  std::vector<std::uint64_t> all(p.size());
  std::iota(all.begin(), all.end(), std::uint64_t{0});
  ContactRecords records;
  collect_records(
      full, all, [](std::size_t, std::size_t) { return true; }, records);
  // A Simulation over the owned particles (the scalars and search method from `full`); assemble
  // then gives it the ghosts and the contact list.
  SimulationState start;
  OwnedSet o = unpack_owned(p, owned, owned_count);
  start.particles = std::move(o.p);
  start.wall_history = std::move(o.wall);
  start.time = full.time;
  start.dt = full.dt;
  start.drum_omega = full.drum_omega;
  start.drum_angle = full.drum_angle;
  start.steps = full.steps;
  start.search_method = full.search_method;
  start.contact_state_size = full.contact_state_size;
  auto sim = std::make_unique<Simulation>(scene, std::move(start));
  assemble(*sim, owned, owned_count, ghosts, std::move(records));
  sim->set_domain(this);
  return sim;
}

void MpiDomain::refresh_ghosts(Simulation& sim, double moved) {
  // `moved` is already every rank's bound: all ranks take the same branch.
  moved_ += moved;
  // The bound only grows; once it passes half the skin, the real displacements decide (one more
  // reduction), as the serial Verlet list checks its particles only when its bound says so.
  if (!(2.0 * moved_ <= options_.skin)) moved_ = measured_displacement(sim);
  const bool rebalance_due =
      options_.rebalance_every > 0 && sim.steps() + 1 - last_balance_ >= options_.rebalance_every;
  if (!(2.0 * moved_ <= options_.skin) || rebalance_due) {
    if (rebalance_due) rebalance(sim);
    exchange(sim);
  } else {
    forward(sim);
  }
}

double MpiDomain::measured_displacement(const Simulation& sim) {
  const Particles& p = sim.particles();
  const double period = options_.period_z.value_or(0.0);
  double d2 = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (sim.is_ghost(i)) continue;
    d2 = std::max(d2, nearest_image(p.position[i], reference_[i], period).squaredNorm());
  }
  return comm_.max(std::sqrt(d2));
}

void MpiDomain::forward(Simulation& sim) {
  Particles& p = sim.local_particles();
  for (std::size_t q = 0; q < send_.size(); ++q) {
    std::vector<double>& b = send_buf_[q];
    b.clear();
    for (const Index i : send_[q]) {
      for (const Vec3* v : {&p.position[i], &p.velocity[i], &p.omega[i]}) {
        b.insert(b.end(), v->data(), v->data() + 3);
      }
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

void MpiDomain::rebalance(const Simulation& sim) {
  const Particles& p = sim.particles();
  std::vector<double> mine;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (sim.is_ghost(i)) continue;
    mine.insert(mine.end(), p.position[i].data(), p.position[i].data() + 3);
  }
  const std::vector<double> all = comm_.all_gather(mine);
  std::vector<Vec3> x(all.size() / 3);
  for (std::size_t k = 0; k < x.size(); ++k)
    x[k] = Vec3(all[3 * k], all[3 * k + 1], all[3 * k + 2]);
  decomposition_ = rcb_decompose(x, {}, options_.domain, comm_.size());
  last_balance_ = sim.steps() + 1;
  ++rebalances_;
}

void MpiDomain::exchange(Simulation& sim) {
  const SimulationState old = sim.state();
  const Particles& p = old.particles;
  const auto& ghost = sim.ghost_mask();
  const auto r = static_cast<std::size_t>(comm_.size());
  // Where each owned particle goes (-1: stays), and the migrants' bytes per destination.
  std::vector<int> dest(p.size(), -1);
  std::vector<std::vector<std::byte>> parts(r), recs(r);
  std::vector<std::size_t> migrants(r, 0), records_to(r, 0);
  std::vector<std::byte> owned;
  std::size_t owned_count = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (ghost[i] != 0) continue;
    const int q = rcb_owner(decomposition_, p.position[i]);
    if (q == comm_.rank()) {
      pack_particle(p, i, slot_[i], old.wall_history[i], owned);
      ++owned_count;
      continue;
    }
    dest[i] = q;
    pack_particle(p, i, slot_[i], old.wall_history[i], parts[static_cast<std::size_t>(q)]);
    ++migrants[static_cast<std::size_t>(q)];
  }
  // Contact records: ours where one particle was owned here, and a copy to each migrant's rank.
  ContactRecords records;
  collect_records(
      old, slot_, [&](std::size_t i, std::size_t j) { return !ghost[i] || !ghost[j]; }, records);
  for (std::size_t k = 0; k < records.size(); ++k) {
    const auto i = static_cast<std::size_t>(
        std::lower_bound(slot_.begin(), slot_.end(), records.a[k]) - slot_.begin());
    const auto j = static_cast<std::size_t>(
        std::lower_bound(slot_.begin(), slot_.end(), records.b[k]) - slot_.begin());
    for (const int q : {dest[i], dest[j] != dest[i] ? dest[j] : -1}) {
      if (q < 0) continue;
      records.pack(k, recs[static_cast<std::size_t>(q)]);
      ++records_to[static_cast<std::size_t>(q)];
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
  for (const auto& msg : in) {
    if (!msg.empty()) owned_count += read_message(msg, p, owned, records);
  }
  assemble(sim, owned, owned_count, {}, std::move(records));
  ++exchanges_;
}

void MpiDomain::reorder(Simulation& sim) {
  // The serial run's re-ordering (morton_order): cells of 2 r_max from the smallest coordinates of
  // all particles, ties by the current order; here every rank sorts every owned key.
  const Particles& p = sim.particles();
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (sim.is_ghost(i)) continue;
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p.position[i][k]);
  }
  comm_.min3(lo);
  const Vec3 origin(lo[0], lo[1], lo[2]);
  std::vector<std::uint64_t> key(p.size()), mine;
  for (std::size_t i = 0; i < p.size(); ++i) {
    key[i] = morton_key(p.position[i], origin, cell_);
    if (sim.is_ghost(i)) continue;
    mine.push_back(key[i]);
    mine.push_back(slot_[i]);
  }
  const std::vector<std::uint64_t> flat = comm_.all_gather(mine);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> all(flat.size() / 2);
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = {flat[2 * k], flat[2 * k + 1]};
  std::sort(all.begin(), all.end());
  std::vector<std::uint64_t> next(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto it = std::lower_bound(all.begin(), all.end(), std::pair{key[i], slot_[i]});
    next[i] = static_cast<std::uint64_t>(it - all.begin());
  }
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
  b.comm_seconds = comm_.seconds();
  return b;
}

}  // namespace drumlab
