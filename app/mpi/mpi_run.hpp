#pragma once
// `drumlab-mpi run`: one scene on the ranks of MPI_COMM_WORLD (engine/parallel/mpi/mpi_domain.hpp),
// with `drumlab run`'s options, output schedule and summary (app/run/). Rank 0 fills the scene
// (or reads the checkpoint) and resolves search "auto" (a restart with a named method is read in
// shares by every rank instead), the particles are cut by RCB, then every rank drives its part
// through a RunSession: settle and turn the drum together, the writers of app/mpi/mpi_outputs.hpp
// called on every rank at the scheduled frames. Checkpoints and series are written in the serial
// layout, so `drumlab run --restart` and `drumlab-mpi run --restart` on any rank count continue
// from them, and `drumlab analyze` / `drumlab convert` read the series.
#include <cstdint>
#include <string>

#include <mpi.h>

#include "app/run/run_options.hpp"
#include "engine/parallel/mpi/mpi_domain.hpp"

namespace drumlab::mpi {

struct MpiRunOptions {
  cli::RunOptions run;  ///< `drumlab run`'s options (app/run/run_options.hpp)
  /// Settling and turning steps between balance checks (0: the first cut is kept): by time a
  /// check re-cuts when the slowest rank's work exceeds the mean by more than the threshold, by
  /// count every check re-cuts (MpiDomainOptions).
  std::uint64_t rebalance_every = 200;
  BalanceBy balance = BalanceBy::time;
  double balance_threshold = 0.05;
  /// Gather checkpoints and series on rank 0 and write them there with the serial writer instead
  /// of every rank writing its share (parallel HDF5): for file systems without working MPI-IO.
  bool gather_output = false;
};

/// Runs the scene and prints (on rank 0) what `drumlab run` prints, then the decomposition's
/// lines; throws InputError / UnstableError as `drumlab run` does (on every rank alike).
void run_mpi(MPI_Comm comm, const MpiRunOptions& options);

}  // namespace drumlab::mpi
