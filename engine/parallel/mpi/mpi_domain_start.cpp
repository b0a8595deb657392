// MpiDomain's start: rank 0's whole state cut and sent part by part (distribute), or every
// rank's share of a checkpoint cut by the distributed RCB and sent to its owners and ghost
// holders (distribute_shares); each rank then builds its Simulation (start_local).
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
  scalars.carrier_angle = share.carrier_angle;
  scalars.carrier_omega = share.carrier_omega;
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

}  // namespace drumlab
