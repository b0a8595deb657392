#pragma once
// What a Simulation allocates, from the sizes of the containers it keeps: the particle arrays,
// the wall and pair contact history, the force-loop and re-ordering scratch, the wall candidates,
// and the search of its method (grid slots and cells, a Verlet list and its builder). Checked
// against the heap measured for small runs (tests/unit/test_memory_estimate.cpp).
#include <cstddef>
#include <string_view>

namespace drumlab {

/// The quantities the estimate depends on.
struct MemoryShape {
  std::size_t particles = 0;
  /// Pairs in the contact list per particle (each pair once): the touching ones, or with a
  /// Verlet list every pair within the skin.
  double listed_pairs_per_particle = 0.0;
  double grid_cells = 0.0;  ///< cells of the search grid (dense index), 0 without one
  bool rotation = true;     ///< a torque is integrated (friction or rolling resistance)
  bool reorder = true;      ///< particles are re-ordered now and then (performance.sort_every > 0)
  int threads = 1;          ///< OpenMP threads: from 2 on, the parallel pair loop's buffers
};

struct MemoryEstimate {
  double per_particle = 0.0;  ///< bytes per particle, its share of the pairs included
  double particles = 0.0;
  double grid = 0.0;  ///< bytes of the grid cells
  double total() const { return per_particle * particles + grid; }
};

/// The heap a Simulation with search `method` holds for `shape`. Throws InputError for an
/// unknown method.
MemoryEstimate estimate_memory(std::string_view method, const MemoryShape& shape);

/// Pairs per particle in the contact list of a settled bed: ~6 touching neighbours (3 pairs); a
/// Verlet list with skin s (in smallest radii) also lists the neighbours within the skin.
double settled_pairs_per_particle(bool verlet, double skin);

}  // namespace drumlab
