#pragma once
// The output writers of `run`/`demo`/`render` as scheduled FrameObservers, created only for the
// output flags given (a run without them creates no writer and no VTK object); when they write is
// app/run/output_schedule.hpp's, shared with drumlab-mpi:
//   --vtu DIR [--contacts-vtk] [--grid-vtk]   VTU/PVD series (needs the render library)
//   --h5 FILE                                 HDF5 time series + XDMF sidecar (streamed)
//   --agglomerates FILE.csv [--granule-age T] agglomerate statistics per frame + FILE.png
//   --checkpoint FILE [--checkpoint-every K]  checkpoint at the end (and every K steps)
#include <memory>
#include <vector>

#include "app/run/run_options.hpp"

namespace drumlab::cli {

/// Creates the writers requested by `opt`. Throws InputError for an unusable output path (before
/// the run starts) or for --vtu in a build without VTK.
std::vector<std::unique_ptr<FrameObserver>> make_output_observers(const RunOptions& opt);

}  // namespace drumlab::cli
