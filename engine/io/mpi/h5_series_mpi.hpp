#pragma once
// The HDF5 series of a decomposed run written in parallel into one file (parallel HDF5, MPI-IO),
// in the serial series' layout (engine/io/h5_series.hpp, the same H5Series with a parallel
// Access): frame by frame, every rank writes its owned particles' rows (a particle's row is its
// serial slot), rank 0 the appended /time and /step values; the file is flushed and closed after
// each frame (collectively), so a killed run keeps its complete frames; rank 0 writes the XDMF
// sidecar from the particle count all ranks agree on.
#include <filesystem>
#include <span>

#include "engine/io/h5_series.hpp"
#include "engine/parallel/mpi/mpi_comm.hpp"
#include "engine/simulation.hpp"

namespace drumlab {

/// The Access of a series that every rank of `comm` writes. Collective: rank 0 checks that
/// `file` can be written and every rank throws InputError alike if not.
H5Series::Access mpi_series_access(MpiComm& comm, const std::filesystem::path& file);

/// Appends the decomposed run's current state (local particles' serial slots `slots`) as a
/// frame of `series` (made with mpi_series_access). Collective; throws on every rank alike.
void write_frame_mpi(H5Series& series, MpiComm& comm, const Simulation& sim,
                     std::span<const std::uint64_t> slots);

}  // namespace drumlab
