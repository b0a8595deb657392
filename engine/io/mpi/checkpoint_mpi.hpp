#pragma once
// Checkpoints of a decomposed run written in parallel into one file (parallel HDF5, MPI-IO), in
// the serial layout (engine/io/checkpoint.hpp, one layout function for both writers:
// engine/io/checkpoint_layout.hpp), so `drumlab run --restart` and `drumlab-mpi run --restart` on
// any rank count continue from it. Every rank writes its owned particles' rows (a particle's row
// is its serial slot) and their contact records: the records of the run of consecutive rows
// [a, b) start at the number of records of all rows before a, which the ranks learn from one
// all-gather of (first row, record count) per run. Atomic as the serial writer: FILE.tmp-PID,
// renamed by rank 0 once every rank has closed it.
#include <filesystem>
#include <span>
#include <string>

#include "engine/parallel/mpi/mpi_comm.hpp"
#include "engine/simulation.hpp"

namespace drumlab {

/// Writes the checkpoint of the decomposed run `sim` (local particles' serial slots `slots`).
/// Collective; throws InputError on every rank alike (nothing is left under FILE then).
void write_checkpoint_mpi(MpiComm& comm, const Simulation& sim,
                          std::span<const std::uint64_t> slots, const std::filesystem::path& file,
                          const std::string& scene_name);

}  // namespace drumlab
