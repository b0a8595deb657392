// The step's side of MpiDomain: whether an exchange is due, the ghosts' motion, balance checks
// and re-cuts, the serial re-ordering, the gather and the statistics. The start is in
// mpi_domain_start.cpp, the exchanges in mpi_domain_exchange.cpp.
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

MpiDomain::MpiDomain(MPI_Comm comm, MpiDomainOptions options)
    : comm_(comm), options_(std::move(options)) {
  const auto r = static_cast<std::size_t>(comm_.size());
  send_.assign(r, {});
  recv_.assign(r, {});
  send_buf_.assign(r, {});
  recv_buf_.assign(r, {});
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
