#pragma once
// The start of an MPI run (issue 15): rank 0 alone fills the scene or reads the checkpoint, cuts it
// by RCB and sends every other rank its part, so that no other rank ever holds the whole state.
// These are its messages, as bytes. The header, broadcast: the state's scalars, the layout of its
// extra per-particle arrays, the particle count, the largest radius and the cut tree. A rank's
// part: its owned particles, its ghosts by owner and the contact records of the pairs it holds
// (both particles owned or ghosts there), each packed as particle_pack.hpp packs them.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/parallel/ghost_layer.hpp"
#include "engine/parallel/particle_pack.hpp"
#include "engine/parallel/rcb.hpp"

namespace drumlab {

struct StartHeader {
  /// The scalars (time, dt, drum, steps, search method, contact state size); its particles are
  /// none, with the whole state's extra arrays registered (their names and initial values).
  SimulationState state;
  Decomposition decomposition;  ///< nodes and boxes; no owners
  std::uint64_t particles = 0;  ///< in the whole state
  double max_radius = 0.0;      ///< of the whole state, m
};

std::vector<std::byte> pack_start_header(const SimulationState& full, const Decomposition& d);
StartHeader unpack_start_header(std::span<const std::byte> bytes);

struct StartPart {
  std::vector<std::byte> owned;  ///< packed particles, ascending serial slot
  std::size_t owned_count = 0;
  std::vector<std::vector<std::byte>> ghosts;  ///< packed, by owner rank, each ascending
  ContactRecords records;                      ///< of the pairs held on the rank
};

/// Rank q's part of `full` (serial slot = index) under `d`, whose owners are full's particles',
/// with the ghost layer `g` of that decomposition. `held` is scratch: full.particles.size() zeros,
/// left so.
StartPart start_part(const SimulationState& full, const Decomposition& d, const GhostLayer& g,
                     int q, std::vector<std::uint8_t>& held);

/// Contact records as bytes (state size, count, then each record) and back.
std::vector<std::byte> pack_records(const ContactRecords& records);
ContactRecords unpack_records(std::span<const std::byte> bytes);

}  // namespace drumlab
