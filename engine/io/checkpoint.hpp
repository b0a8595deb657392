#pragma once
// Checkpoint files (HDF5): the complete SimulationState, so `drumlab run --restart FILE` continues
// bit-identically. Layout (format "drumlab-checkpoint", version 1):
//   /                  attributes format, version, scene, search_method, time, dt, drum_omega,
//                      drum_angle, steps
//   /particles/        position, velocity, omega, force, torque (N x 3, f64); radius, mass,
//                      inv_mass, inv_inertia (N, f64); size_class (N, u8); id (N, u32)
//   /contacts/         row_start (N + 1 or 0, u64), col (M, u32), history (M x 3, f64)
//   /walls/history     N x 3 wall parts x 3 (f64)
// Doubles are stored as IEEE binary64, so values come back with every bit.
#include <filesystem>
#include <string>

#include "engine/simulation_state.hpp"

namespace drumlab {

/// Builds the file in memory, writes it to FILE.tmp-PID and renames it into place; throws
/// InputError on failure (no file is left under the final name). `scene_name` is recorded for the
/// restart's check.
void write_checkpoint(const std::filesystem::path& file, const SimulationState& state,
                      const std::string& scene_name);

struct Checkpoint {
  SimulationState state;
  std::string scene_name;
  std::size_t particles = 0;  ///< in the file
};

/// Reads a checkpoint; throws InputError for a missing file, another format or inconsistent data.
Checkpoint read_checkpoint(const std::filesystem::path& file);

/// Reads the particles [first, first + count) of a checkpoint (an MPI rank's share of it): their
/// arrays and wall history, and their rows of the contact list, contact_row_start from 0 and
/// contact_col the partners' slots in the whole file (so not a state a Simulation runs); the
/// scalars as read_checkpoint. Throws InputError as read_checkpoint does, and for rows beyond the
/// file's.
Checkpoint read_checkpoint_rows(const std::filesystem::path& file, std::size_t first,
                                std::size_t count);

}  // namespace drumlab
