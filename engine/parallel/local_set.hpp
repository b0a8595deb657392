#pragma once
// A rank's next local set at a migration (engine/parallel/mpi/mpi_domain.cpp), built without
// packing what stays: each particle comes either from a packed record (a migrant, a new ghost, or
// every particle at the distribution) or from the rank's current arrays at its local index (an
// owned particle that stays, a ghost that stays a ghost, whose owner sends only its motion). The
// contact list keeps the current list's entries of the particles that stay and merges in the
// records that came with the migrants. Everything is in the serial run's order (serial slots).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/contact/contact_history.hpp"
#include "engine/parallel/particle_pack.hpp"
#include "engine/simulation_state.hpp"

namespace drumlab {

/// A particle of the next local set: its serial slot, the rank that sends it (-1: owned here),
/// and where its data is: the packed record at `at` (packed_size bytes), or, with at == nullptr,
/// this rank's particle `local` before the exchange, whose position, velocity and angular velocity
/// are replaced by the kPackedMotionBytes at `motion` when that is set.
struct PackedPiece {
  std::uint64_t slot;
  const std::byte* at;
  int source;
  Index local = 0;
  const std::byte* motion = nullptr;
};

/// Fills `out` (the same arrays registered as `p`) and `out_wall` with the particles `seq`, in
/// that order; `p` and `wall` are the current local arrays that pieces with at == nullptr index,
/// `size` the packed size of a particle.
void fill_particles(std::span<const PackedPiece* const> seq, const Particles& p,
                    const WallHistory& wall, std::size_t size, Particles& out,
                    WallHistory& out_wall);

/// The carried contacts of the next local set into s's CSR arrays (state size from `old`):
/// `old`'s entries (i, j) with at least one of the two owned here before (`old_ghost`), both
/// still present (`new_of_old[i] < ghost.size()`), at least one owned after (`ghost`) and a
/// history or state that is not all zero bits (a pair the rebuilt list finds starts with exactly
/// that); then the records (pairs of serial slots, `slot` the next set's slots, increasing) under
/// the same conditions. A pair in both keeps `old`'s entry, a pair twice in the records its first.
void merge_contacts(const ContactList& old, std::span<const std::uint8_t> old_ghost,
                    std::span<const Index> new_of_old, std::span<const std::uint8_t> ghost,
                    std::span<const std::uint64_t> slot, const ContactRecords& records,
                    SimulationState& s);

/// Whether contact k of `history` / `state` (state_size scalars each) holds a non-zero bit.
bool carries_contact(std::span<const Vec3> history, std::span<const double> state,
                     std::size_t state_size, std::size_t k);

}  // namespace drumlab
