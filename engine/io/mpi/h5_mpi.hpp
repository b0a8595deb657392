#pragma once
// Parallel HDF5 (Debian's libhdf5-openmpi-dev, compiled into drumlab_engine_mpi only): one file
// that every rank of a decomposed run opens through MPI-IO and writes its share of, in the layout
// the serial writers make (engine/io/checkpoint_layout.hpp, engine/io/h5_series.hpp). Each rank
// writes the rows of its owned particles: a particle's row is its slot in the serial run's order
// (MpiDomain::slots()), so the file holds what the serial run at that step would write.
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>

#include "engine/io/h5_file.hpp"
#include "engine/parallel/mpi/mpi_comm.hpp"
#include "engine/simulation.hpp"

namespace drumlab::h5 {

/// True on every rank if `ok` on every rank (MPI_Allreduce): the collective check after each
/// step of a parallel write, so that a failure on one rank throws on all of them.
bool all_ok(MPI_Comm comm, bool ok);

/// Runs `work` on rank 0 and tells every rank how it went: an InputError there (an unwritable
/// path, a full disk) is thrown on every rank alike, so that no rank is left waiting in a
/// collective and every rank exits 2 with rank 0's one line. Collective.
void on_root(MPI_Comm comm, const std::function<void()>& work);

/// Creates (truncates) or opens `path` on every rank of `comm` through MPI-IO (no file lock, as
/// the serial series); a new file in the format of its form (a checkpoint `whole`, a series
/// `streamed`). Collective; throws InputError naming the path on every rank alike.
Handle create_mpi_file(MPI_Comm comm, const std::filesystem::path& path, FileFormat format);
Handle open_mpi_file_rw(MPI_Comm comm, const std::filesystem::path& path);
/// Flushes (create) and closes a file opened on every rank; throws InputError on all if any failed.
void close_mpi_file(MPI_Comm comm, Handle& file, const std::filesystem::path& path);

/// The process's collective MPI-IO transfer property list (H5FD_MPIO_COLLECTIVE), made once.
hid_t collective_transfer();

/// Rows of a parallel write of a dataset of `total` rows: this rank's `rows` (increasing) as runs.
Rows rows_of(MPI_Comm comm, hid_t transfer, std::span<const std::uint64_t> rows, hsize_t total);
/// Appends rows [first, first + count) (after the last run) to r's runs.
void add_rows(Rows& r, hsize_t first, hsize_t count);

/// This rank's owned particles in the serial run's order, their serial slots and their rows.
struct OwnedParticles {
  Particles particles;
  WallHistory wall;
  std::vector<std::uint64_t> slot;
  std::size_t total = 0;  ///< particles over all ranks
};
/// The owned (not ghost) particles of a decomposed run's local state. Collective (the total).
OwnedParticles owned_particles(MpiComm& comm, const SimulationState& local,
                               const std::vector<std::uint8_t>& ghost,
                               std::span<const std::uint64_t> slots);

}  // namespace drumlab::h5
