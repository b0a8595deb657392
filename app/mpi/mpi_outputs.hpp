#pragma once
// drumlab-mpi's writers, scheduled as `drumlab run`'s (app/run/output_schedule.hpp): the HDF5
// series (--h5) and the checkpoint written by every rank into one file (parallel HDF5,
// engine/io/mpi/) in the serial layout, or with --gather-output gathered on rank 0 and written
// there by the serial writers; the agglomerate table (--agglomerates) of the state gathered on
// rank 0, found as the serial run finds it (no chart: that needs VTK). Every writer is called on
// every rank (collective); a write that fails on one rank throws on every rank alike. No VTU:
// VTK must not enter this process.
#include <cstdint>
#include <memory>
#include <vector>

#include "app/run/run_options.hpp"
#include "engine/parallel/mpi/mpi_domain.hpp"

namespace drumlab::mpi {

/// What the writers wrote and the seconds it took this rank.
struct OutputTimes {
  std::uint64_t checkpoints = 0, frames = 0;
  double checkpoint_seconds = 0.0, frame_seconds = 0.0;
};

/// The writers `opt` asks for, their paths checked now (before the fill): the series, the
/// checkpoint, the agglomerate table, in the order `drumlab run` calls them. `gather`: write
/// everything from rank 0 (--gather-output). `times` and `domain` must outlive the writers.
/// Collective; InputError on every rank alike.
std::vector<std::unique_ptr<FrameObserver>> make_mpi_outputs(MpiDomain& domain,
                                                             const cli::RunOptions& opt,
                                                             bool gather, OutputTimes& times);

}  // namespace drumlab::mpi
