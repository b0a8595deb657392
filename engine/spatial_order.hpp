#pragma once
// Spatial re-ordering of particles for cache locality (HOOMD's SFCPackTuner, LAMMPS's atom_modify
// sort): particles are ordered along a Morton (Z-order) curve over cells of a given side, so that
// particles close in space are close in memory and a contact's partner is usually in cache.
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/types.hpp"

namespace drumlab {

/// Buffers of a re-ordering, kept between calls so that re-ordering allocates nothing once warm.
struct ReorderBuffers {
  std::vector<Vec3> lows;  ///< each thread's smallest corner
  std::vector<std::pair<std::uint64_t, Index>> keys;
  std::vector<std::pair<std::uint64_t, Index>> sorted;  ///< the sort's other buffer
  std::vector<Index> order;      ///< slot k of the new order holds the particle now at order[k]
  std::vector<Index> new_index;  ///< inverse: particle i moves to slot new_index[i]
  std::vector<Vec3> vec3;
  std::vector<double> real;
  std::vector<std::uint8_t> byte;
  std::vector<Index> index;
};

/// The Morton code of x's cell (side `cell` > 0, m) counted from `lo`, the smallest coordinates.
std::uint64_t morton_key(const Vec3& x, const Vec3& lo, double cell);

/// Fills b.order and b.new_index: particles sorted by the Morton code of their cell (side
/// `cell` > 0, m), ties by current index, so the order is deterministic.
void morton_order(std::span<const Vec3> position, double cell, ReorderBuffers& b);

/// Re-orders `values` so that values_new[k] = values_old[order[k]]; `scratch` is reused.
template <class T>
void apply_order(std::vector<T>& values, std::span<const Index> order, std::vector<T>& scratch) {
  scratch.resize(values.size());
  const auto n = static_cast<std::int64_t>(order.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < n; ++k) {
    scratch[static_cast<std::size_t>(k)] = values[order[static_cast<std::size_t>(k)]];
  }
  values.swap(scratch);
}

}  // namespace drumlab
