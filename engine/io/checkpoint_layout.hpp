#pragma once
// The checkpoint's layout (engine/io/checkpoint.hpp) as one function used by both writers: the
// serial one (write_checkpoint: all rows from the whole state) and the parallel one
// (engine/io/mpi/checkpoint_mpi.hpp: every rank its rows of each dataset from its share).
#include <string>

#include "engine/io/h5_file.hpp"
#include "engine/simulation_state.hpp"

namespace drumlab {

/// The rows a writer writes of the three kinds of dataset: per particle (N rows, in the serial
/// run's order), per contact record (M rows, in CSR order) and /contacts/row_start (N + 1 rows).
struct CheckpointRows {
  h5::Rows particles, records, row_start;
};

/// Writes the attributes, /particles, /contacts and /walls of `state` into `file`. Serial: `rows`
/// all rows (default), `state` the whole state. Parallel: `state` holds this rank's rows of each
/// kind (its particles, their contact records with contact_col as serial slots, and their
/// row_start values, offsets into the whole file's records), the attributes the same on every
/// rank.
void write_checkpoint_datasets(hid_t file, const SimulationState& state,
                               const std::string& scene_name, const CheckpointRows& rows = {});

}  // namespace drumlab
