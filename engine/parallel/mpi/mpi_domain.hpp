#pragma once
// One rank's side of the MPI domain decomposition (issue 15; design in engine/README.md, "Domain
// decomposition"). The particles are cut into boxes by RCB (engine/parallel/rcb.hpp); a rank keeps
// its owned particles and, as ghosts, the other ranks' particles within the ghost reach of its box
// (engine/parallel/ghost_layer.hpp), all in the serial run's order (each particle's slot in the
// serial run, `slots()`), so its pair loop sums every owned particle's force in the serial order
// (ContactList::set_row_keys) and the trajectory is the serial one, bit for bit.
//
// Every step (refresh_ghosts, between drift and search) the owners send their ghosts' position,
// velocity and angular velocity to the neighbouring ranks. When the two largest displacements since
// the last exchange (bounded by the drifts' bounds, measured once the bound passes half the skin)
// sum to more than the skin, or a re-balance is due, particles migrate to the rank whose box holds
// them with their arrays, wall history and contact records, and the ghost layer is rebuilt (kept
// ghosts get their motion only). One rank does none of this. At a re-ordering step the ranks agree
// on the serial run's new order (same Morton keys and ties as Simulation::reorder_particles).
//
// Its definitions by concern: mpi_domain_start.cpp (distribute, distribute_shares, a rank's
// Simulation), mpi_domain_exchange.cpp (migration, the ghost layer, the next local set),
// mpi_domain.cpp (the step's hooks: ghost motion, balance checks and re-cuts, re-ordering; the
// gather and the statistics); domain_messages.hpp holds the message pieces they share.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "engine/parallel/domain_hooks.hpp"
#include "engine/parallel/ghost_layer.hpp"
#include "engine/parallel/local_set.hpp"
#include "engine/parallel/mpi/mpi_bridge_events.hpp"
#include "engine/parallel/mpi/mpi_comm.hpp"
#include "engine/parallel/particle_pack.hpp"
#include "engine/parallel/rcb.hpp"
#include "engine/parallel/start_message.hpp"
#include "engine/simulation.hpp"

namespace drumlab {

/// What an RCB re-balance equalises: the particle count, or each rank's measured computing time
/// (LAMMPS' `fix balance ... weight time`): every particle weighs its rank's seconds of work (wall
/// time outside MPI) since the last check over its owned count, so the cuts move work from the
/// ranks that computed longest.
enum class BalanceBy { count, time };

struct MpiDomainOptions {
  GhostReach reach;   ///< ghost reach (m), ghost_reach() with the skin
  double skin = 0.0;  ///< m: particles migrate when one moved more than half of it
  std::optional<double> period_z;
  Box domain;                         ///< drum_domain of the scene
  std::uint64_t rebalance_every = 0;  ///< steps between balance checks (0: never re-balance)
  BalanceBy balance = BalanceBy::time;
  /// By time: a check re-cuts only when the slowest rank's work exceeds the mean by more than
  /// this share (0: at every check). By count every check re-cuts.
  double balance_threshold = 0.05;
};

struct MpiBalance {
  std::size_t owned_min = 0, owned_max = 0;
  double owned_mean = 0.0;
  std::uint64_t exchanges = 0, rebalances = 0;
  /// By time: the slowest rank's work over the mean at the first and at the last balance check
  /// (0: no check yet).
  double first_imbalance = 0.0, last_imbalance = 0.0;
  /// Ghost records sent at exchanges over all ranks: in full (new ghosts) and motion only (kept).
  std::uint64_t ghosts_new = 0, ghosts_kept = 0;
  std::uint64_t bridge_events = 0;  ///< liquid bridge events replayed (the same on every rank)
  double comm_seconds = 0.0;        ///< this rank's seconds inside MPI
  /// This rank's wall seconds in exchanges (migration, ghost layer, the next local set; the list
  /// rebuild that follows is the search's).
  double exchange_seconds = 0.0;
  /// This rank's wall seconds finding new cuts at re-balances (rcb_decompose_mpi).
  double recut_seconds = 0.0;
};

class MpiDomain final : public DomainHooks {
 public:
  MpiDomain(MPI_Comm comm, MpiDomainOptions options);

  /// This rank's part of the whole state `full` (particles in the serial run's order), as a
  /// Simulation wired to this domain. `full` is rank 0's (none on the others): rank 0 cuts it,
  /// sends each rank its part (engine/parallel/start_message.hpp) and frees it. Bad input met by
  /// any rank (its part refused by Simulation) is thrown on every rank. Collective.
  std::unique_ptr<Simulation> distribute(const SceneConfig& scene,
                                         std::optional<SimulationState> full);
  /// This rank's part of a checkpoint that every rank read a share of (no rank holds the whole
  /// state): `share` holds the rows [first, first + its size) of the file's `total` particles
  /// (read_checkpoint_rows), with the scalars; the ranks cut all shares by rcb_decompose_mpi and
  /// send each particle to its owner and to the ranks that hold it as a ghost, and each contact
  /// record to the ranks that hold its row's particle. Bad input met by any rank (its part
  /// refused by Simulation) is thrown on every rank. Collective.
  std::unique_ptr<Simulation> distribute_shares(const SceneConfig& scene, SimulationState share,
                                                std::uint64_t first, std::uint64_t total);
  /// Particles of the whole state at the distribution.
  std::uint64_t particles() const { return particles_; }
  /// The whole state on rank 0, particles in the serial run's order (nothing elsewhere): what a
  /// serial run at this step would export. Collective.
  std::optional<SimulationState> gather(const Simulation& sim);
  /// This rank's seconds inside MPI so far (distribution, exchanges, reductions).
  double comm_seconds() const { return comm_.seconds(); }
  /// Owned counts over ranks and this rank's communication time. Collective.
  MpiBalance balance(const Simulation& sim);

  double max(double v) override { return comm_.max(v); }
  void max(std::span<double> v) override { comm_.max(v); }
  double min(double v) override { return comm_.min(v); }
  double sum(double v) override { return comm_.sum(v); }
  std::uint64_t sum(std::uint64_t v) override { return comm_.sum(v); }
  void reorder(Simulation& sim) override;
  void refresh_ghosts(Simulation& sim, double moved) override;
  /// The liquid's ordered pass over all ranks (none on one rank: its films are all its own).
  BridgeEventHooks* bridge_events() override { return comm_.size() > 1 ? &events_ : nullptr; }

  MpiComm& comm() { return comm_; }
  const std::vector<std::uint64_t>& slots() const { return slot_; }
  /// Gives every ghost of the current local set its owner's value of a per-particle array
  /// (`values`, local order, one per local particle), as the step refreshes ghost motion.
  /// Collective.
  void copy_to_ghosts(std::span<std::uint64_t> values);

 private:
  /// The Simulation of this rank's part (owned particles packed, ghosts by owner, records) with
  /// the state's scalars (`scalars`, whose particles register the extra arrays), wired to this
  /// domain; decomposition_ and cell_ set. A part the Simulation refuses on any rank throws its
  /// InputError on every rank. Collective.
  std::unique_ptr<Simulation> start_local(const SceneConfig& scene, SimulationState scalars,
                                          StartPart part);
  /// Migration, optional re-balance and a new ghost layer; replaces sim's particles.
  void exchange(Simulation& sim);
  void forward(Simulation& sim);
  /// The two largest displacements of all ranks' particles since the last exchange (m), largest
  /// first. Collective.
  std::pair<double, double> measured_displacement(const Simulation& sim);
  /// At a balance check: whether to re-cut now (by time: the measured imbalance against the
  /// threshold; this rank's work weight kept for rebalance). Starts the next window. Collective.
  bool balance_check(const Simulation& sim);
  void rebalance(const Simulation& sim);
  /// The next local set from the owned particles `owned` (sorted by serial slot) and the ghosts:
  /// at a migration (`migration`) exchanged here, the ghosts that stay ghosts getting only their
  /// motion from their owners, and the current contact list's entries kept besides `records`; at
  /// the distribution the ghosts' records by source rank `given`, the contacts from `records`
  /// alone. Sets the slots, send and receive lists and reference positions, replaces sim's
  /// particles.
  void assemble(Simulation& sim, std::vector<PackedPiece> owned,
                const std::vector<std::vector<std::byte>>& given, ContactRecords records,
                bool migration);
  /// The messages of the other ranks (to send): to each rank the records of its new ghosts
  /// among `owned` (sorted by serial slot), then the slots and motion of the ghosts it keeps
  /// (those in `sent`, by rank); send_ lists them in that order, by their index in `owned`.
  std::vector<std::vector<std::byte>> ghost_packs(
      std::span<const PackedPiece> owned, const Simulation& sim,
      const std::vector<std::vector<std::uint64_t>>& sent);
  /// Appends the ghosts of the messages `in` (by source rank) to `ghosts`: new ones as received,
  /// kept ones as this rank's current copy with their owner's motion.
  void received_ghosts(const std::vector<std::vector<std::byte>>& in, std::size_t size,
                       std::vector<PackedPiece>& ghosts) const;

  MpiComm comm_;
  MpiDomainOptions options_;
  Decomposition decomposition_;
  std::vector<std::uint64_t> slot_;              ///< serial slot of each local particle
  std::vector<std::vector<Index>> send_, recv_;  ///< local slots per neighbour rank
  std::vector<std::vector<double>> send_buf_, recv_buf_;
  double moved_ = 0.0;           ///< bound on the largest displacement since the last exchange, m
  std::vector<Vec3> reference_;  ///< positions at the last exchange
  double cell_ = 0.0;            ///< Morton cell, 2 r_max over all ranks
  std::uint64_t particles_ = 0;
  std::uint64_t last_balance_ = 0;  ///< step of the last balance check (or of the distribution)
  double window_wall_ = 0.0, window_comm_ = 0.0;  ///< MPI_Wtime and comm seconds at its start
  double work_weight_ = 1.0;  ///< by time: this rank's work per owned particle in the last window
  double first_imbalance_ = 0.0, last_imbalance_ = 0.0;
  std::uint64_t exchanges_ = 0, rebalances_ = 0;
  double exchange_seconds_ = 0.0, recut_seconds_ = 0.0;
  std::uint64_t ghosts_new_ = 0, ghosts_kept_ = 0;  ///< this rank's, at exchanges
  MpiBridgeEvents events_{comm_, slot_};
  // Kept between exchanges so that each one refills memory instead of allocating (and faulting
  // in) hundreds of MB on a large drum: the particles and contact arrays the last one replaced
  // (refilled by the next), the arrived migrants' bytes.
  SimulationState spare_;
  std::vector<std::byte> owned_bytes_;
};

}  // namespace drumlab
