#pragma once
// What drumlab-mpi prints besides `drumlab run`'s summary (app/run/run_report.hpp, printed by the
// same code with numbers over all ranks): the ranks, the decomposition's balance and
// communication, the ghosts, the bridge events and the writers' seconds.
#include <cstdint>

#include "app/mpi/mpi_outputs.hpp"
#include "app/run/run_report.hpp"
#include "engine/parallel/mpi/mpi_domain.hpp"

namespace drumlab::mpi {

struct MpiRunSummary {
  int ranks = 1;
  int threads = 1;
  MpiBalance balance;           ///< owned counts, exchanges, re-balances, imbalance, ghosts, events
  double comm_share_max = 0.0;  ///< largest share of a rank's time inside MPI
  double comm_share_mean = 0.0;
  double exchange_seconds = 0.0;  ///< in exchanges, slowest rank
  double recut_seconds = 0.0;     ///< finding new cuts at re-balances, slowest rank
  BalanceBy balance_by = BalanceBy::time;
  std::uint64_t rebalance_every = 0;
  double balance_threshold = 0.0;
  bool wet = false;    ///< liquid migration: films change at bridge events
  OutputTimes output;  ///< seconds: the slowest rank's
};

/// `phase` of this rank made the whole run's, as RunSummary says: search counters summed, step
/// timers averaged, the slowest rank's wall, CPU and output seconds. Collective.
void reduce_phase(MpiDomain& domain, PhaseStats& phase);

/// Prints the decomposition's lines (rank 0 calls it).
void print_decomposition(const MpiRunSummary& s);

}  // namespace drumlab::mpi
