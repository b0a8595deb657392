#pragma once
// What a decomposition costs per time step, on paper: the bytes each rank receives for its ghosts
// and the communication time they take under a network model, against the compute time of its
// owned particles at a measured one-core rate.
//
// The exchange design this assumes (and the future MPI code follows): every step each rank sends
// the position, velocity and angular velocity of its particles that are another rank's ghosts
// (3 x 3 doubles = 72 bytes per ghost, one message per neighbouring rank), and computes every pair
// that has one of its own particles in it, including pairs with ghosts (both ranks compute a pair
// that crosses a boundary, LAMMPS' "newton off"). No forces travel back, and the force on a
// particle is summed on its owner alone, in an order the decomposition does not change.
// Migration and ghost-list updates happen at Verlet rebuilds only and are not counted per step.
// Given the pairs the force loop visits, a rank's compute also holds the pairs across its boundary
// that its neighbour computes too.
#include <cstddef>
#include <span>
#include <vector>

#include "engine/parallel/ghost_layer.hpp"
#include "engine/parallel/rcb.hpp"

namespace drumlab {

/// Bytes per ghost particle per step: position, velocity and angular velocity as doubles.
inline constexpr std::size_t kGhostBytesPerStep = 3 * 3 * sizeof(double);

struct NetworkModel {
  double bandwidth = 10e9;  ///< bytes/s per rank (10 GB/s)
  double latency = 2e-6;    ///< s per message
};

struct RankCost {
  std::size_t owned = 0;
  std::size_t ghosts = 0;
  std::size_t neighbours = 0;  ///< ranks it receives from (messages per step)
  double bytes = 0.0;          ///< received per step
  double compute = 0.0;        ///< s per step: its share of the work x all particles / rate
  std::size_t across = 0;      ///< listed pairs with one particle here and one elsewhere
  double comm = 0.0;           ///< s per step: neighbours x latency + bytes / bandwidth
};

struct DecompositionCost {
  std::vector<RankCost> ranks;
  double rate = 0.0;          ///< one-core particle-steps/s the compute times assume
  double step_serial = 0.0;   ///< s per step on one core: all particles / rate
  double step_compute = 0.0;  ///< max over ranks of compute
  double step_comm = 0.0;     ///< max over ranks of comm
  /// Pair work done twice (the pairs across boundaries) over all pairs; 0 without a pair list.
  double duplicated = 0.0;
  /// Estimated step time with the exchange not overlapped with computing: the slowest rank's
  /// compute plus the slowest exchange.
  double step() const { return step_compute + step_comm; }
  double speedup() const { return step() > 0.0 ? step_serial / step() : 0.0; }
};

/// The pairs the force loop visits as a CSR list (row i's partners col[k], k in [row[i],
/// row[i + 1]); a Verlet list or the contacts): per rank, those with one particle on the rank and
/// the other elsewhere, which both ranks compute; and how many there are in all.
struct PairsAcross {
  std::vector<std::size_t> across;
  std::size_t total = 0;
};
PairsAcross pairs_across(const Decomposition& d, std::span<const std::size_t> row,
                         std::span<const Index> col);

/// `rate`: one-core particle-steps/s (> 0). Each rank's compute time is its share of
/// `rank_work` (per rank, any unit; empty: the weight the decomposition balanced) times the
/// one-core step time of all particles. With `pairs`, a rank also computes again its neighbours'
/// share of the pairs across: half of its pairs across on average (the other half are its own
/// share already), each costed as a whole step's time over all pairs (as if the step were all pair
/// work: an upper bound, the pair loop and the search take 85-90 % of a step).
DecompositionCost decomposition_cost(const Decomposition& d, const GhostLayer& g, double rate,
                                     const NetworkModel& net,
                                     std::span<const double> rank_work = {},
                                     const PairsAcross* pairs = nullptr);

}  // namespace drumlab
