#pragma once
// The pieces of MpiDomain's messages, shared by its start (mpi_domain_start.cpp), its exchanges
// (mpi_domain_exchange.cpp) and its gather (mpi_domain.cpp): packed particle records sorted by
// serial slot, unpacked into owned sets, and message sections (a count, then that many items).
// Internal to engine/parallel/mpi/.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/parallel/local_set.hpp"
#include "engine/parallel/particle_pack.hpp"

namespace drumlab::domain_messages {

/// Whether a and b hold the same extra arrays (names, in order).
bool same_arrays(const Particles& a, const Particles& b);

/// Owned particles, sorted by serial slot.
struct OwnedSet {
  Particles p;
  WallHistory wall;
  std::vector<std::uint64_t> slot;
};

/// The `count` records packed in `bytes`, sorted by serial slot.
std::vector<PackedPiece> sorted_pieces(std::span<const std::byte> bytes, std::size_t count,
                                       std::size_t size);

/// Unpacks `count` particles from `bytes` in the order of their serial slots.
OwnedSet unpack_owned(const Particles& like, std::span<const std::byte> bytes, std::size_t count);

/// A section of a message: a count, then that many packed items.
void put_count(std::vector<std::byte>& out, std::size_t n);

/// Reads a message of two sections (particles, then contact records): appends the particles'
/// bytes to `owned` and the records to `records`; returns the particle count.
std::size_t read_message(std::span<const std::byte> msg, const Particles& like,
                         std::vector<std::byte>& owned, ContactRecords& records);

}  // namespace drumlab::domain_messages
