#pragma once
// The HDF5 series of a decomposed run written in parallel into one file (parallel HDF5, MPI-IO),
// in the serial series' layout (engine/io/h5_series.hpp, the same H5Series with a parallel
// Access): frame by frame, every rank writes its owned particles' rows (a particle's row is its
// serial slot), rank 0 the appended /time and /step values; the file is flushed and closed after
// each frame (collectively), so a killed run keeps its complete frames; rank 0 writes the XDMF
// sidecar from the particle count all ranks agree on. A scene with bonds adds the bond graph
// (each rank its rows of the bond list) and the agglomerate labels, found without gathering.
#include <filesystem>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/io/h5_series.hpp"
#include "engine/parallel/mpi/mpi_domain.hpp"
#include "engine/simulation.hpp"

namespace drumlab {

/// The Access of a series that every rank of `comm` writes. Collective: rank 0 checks that
/// `file` can be written and every rank throws InputError alike if not.
H5Series::Access mpi_series_access(MpiComm& comm, const std::filesystem::path& file);

/// Appends the current state of `sim` (the local set of `domain`) as a frame of `series` (made
/// with mpi_series_access), as write_series_frame would the serial run's: for a scene with bonds
/// with its bond graph and agglomerate labels under the criterion for `granule`
/// (granule_options), found where the particles are (engine/parallel/mpi/bond_frame_mpi.hpp).
/// Collective; throws on every rank alike.
void write_frame_mpi(H5Series& series, MpiDomain& domain, const Simulation& sim,
                     const GranuleCriterion& granule);

}  // namespace drumlab
