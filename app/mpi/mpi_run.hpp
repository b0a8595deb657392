#pragma once
// `drumlab-mpi run`: one scene on the ranks of MPI_COMM_WORLD (engine/parallel/mpi/mpi_domain.hpp).
// Every rank fills the scene with the same seed (or reads the same checkpoint), rank 0 resolves
// search "auto" and tells the others, the particles are cut by RCB, then the ranks settle and turn
// the drum together. Checkpoints are written by every rank into one file (parallel HDF5,
// engine/io/mpi/) in the serial layout (engine/io/checkpoint.hpp), so `drumlab run --restart` and
// `drumlab-mpi run --restart` on any rank count continue from them; an HDF5 series (--h5) is
// written the same way (a scene with bonds: gathered on rank 0, see MpiRunOptions::h5), so
// `drumlab analyze` and `drumlab convert` read it. --gather-output
// gathers both on rank 0 and writes them with the serial writers instead.
#include <cstdint>
#include <string>

#include <mpi.h>

#include "engine/parallel/mpi/mpi_domain.hpp"
#include "engine/session/run_session.hpp"

namespace drumlab::mpi {

struct MpiRunOptions {
  SessionOptions session;
  int threads = 1;
  std::string checkpoint;  ///< written at the end (and every checkpoint_every steps)
  std::uint64_t checkpoint_every = 0;
  /// Settling and turning steps between balance checks (0: the first cut is kept): by time a
  /// check re-cuts when the slowest rank's work exceeds the mean by more than the threshold, by
  /// count every check re-cuts (MpiDomainOptions).
  std::uint64_t rebalance_every = 200;
  BalanceBy balance = BalanceBy::time;
  double balance_threshold = 0.05;
  /// HDF5 series (engine/io/h5_series.hpp), written by every rank in the serial layout: frame 0
  /// at the start of the turn, then every `every` turning steps (0: 1/100 of the turn), as
  /// `drumlab run --h5` writes it. A scene with bonds (scene_has_bonds) is always gathered: its
  /// frames carry the bond graph and the agglomerate labels, found on rank 0 on the whole graph as
  /// `drumlab run` finds them.
  std::string h5;
  std::uint64_t every = 0;
  double granule_age = -1.0;  ///< the labels' criterion (s); < 0: one drum revolution
  /// Gather checkpoints and series on rank 0 and write them there with the serial writer instead
  /// of every rank writing its share (parallel HDF5): for file systems without working MPI-IO.
  bool gather_output = false;
};

struct MpiRunSummary {
  std::string scene;
  std::string method;
  std::size_t particles = 0;
  int ranks = 1;
  int threads = 1;
  std::uint64_t settle_steps = 0, turn_steps = 0;
  double seconds = 0.0;  ///< wall time of settling and turning
  double turn_seconds = 0.0;
  std::size_t owned_min = 0, owned_max = 0;
  double owned_mean = 0.0;
  double comm_share_max = 0.0;  ///< largest share of a rank's time inside MPI
  double comm_share_mean = 0.0;
  std::uint64_t exchanges = 0, rebalances = 0;
  double exchange_seconds = 0.0;  ///< in exchanges, slowest rank
  double recut_seconds = 0.0;     ///< finding new cuts at re-balances, slowest rank
  /// Seconds in each phase of the step (StepTimers; integration includes the ghost refresh and
  /// the exchanges), mean over ranks.
  StepTimers split;
  BalanceBy balance = BalanceBy::time;
  std::uint64_t rebalance_every = 0;
  double balance_threshold = 0.0;
  double first_imbalance = 0.0, last_imbalance = 0.0;  ///< MpiBalance (by time)
  std::uint64_t ghosts_new = 0, ghosts_kept = 0;       ///< ghost records at exchanges, all ranks
  bool wet = false;                 ///< liquid migration: films change at bridge events
  std::uint64_t bridge_events = 0;  ///< of all ranks, replayed in the serial order (2+ ranks)
  std::uint64_t checkpoints = 0, frames = 0;             ///< written
  double checkpoint_seconds = 0.0, frame_seconds = 0.0;  ///< writing them, slowest rank
  std::string search_reason;                             ///< auto's reason, if it chose
};

/// Runs the scene; throws InputError / UnstableError as `drumlab run` does (on every rank).
MpiRunSummary run_mpi(MPI_Comm comm, const MpiRunOptions& options);

}  // namespace drumlab::mpi
