#pragma once
// The position of each rank's keys in the order of all ranks' keys, without gathering them: a
// sample sort. Each rank sorts its keys and contributes regular samples; the gathered samples give
// one splitter per rank boundary; every key goes to the rank of its splitter range (one
// all-to-all), which sorts what it received and numbers it after the ranges below it; the numbers
// go back to the keys' ranks (a second all-to-all). Each rank moves and sorts about N / ranks keys
// and 64 samples per rank, where gathering every key on every rank moves and sorts all N. The
// result is exact whatever the splitters: they only decide how evenly the ranges fall.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/parallel/mpi/mpi_comm.hpp"

namespace drumlab {

/// A sort key: a Morton key with the serial slot as tie-break (unique over all ranks).
struct OrderKey {
  std::uint64_t key = 0, slot = 0;
  friend bool operator<(const OrderKey& a, const OrderKey& b) {
    return a.key != b.key ? a.key < b.key : a.slot < b.slot;
  }
};

/// For each of `mine`, the number of keys of all ranks that precede it (its index in the
/// ascending order of all ranks' keys, which must be distinct). Collective.
std::vector<std::uint64_t> global_ranks(MpiComm& comm, std::span<const OrderKey> mine);

}  // namespace drumlab
