#pragma once
// The bond graph, agglomerate labels and wall-bridge liquid of a decomposed run's frame, found
// where the particles are (no rank gathers the state): the values, and the bond order, that
// write_series_frame (engine/io/h5_series_frame.hpp) finds on the serial run's whole state.
// * Bonds: a rank lists the bonds whose end with the smaller serial slot it owns (it holds the
//   other end as a ghost, or owns it too; a pair of two ghosts is left to their owners). A
//   bond's row in the frame's list is its place in the order of (smaller slot, larger slot) over
//   all ranks (global_ranks, a sample sort): the serial list's (i, j) order.
// * Labels: the smallest stable id in each particle's component of the bonds that join
//   (bond_joins, the granule criterion). A rank joins its particles (owned and ghosts) along its
//   bonds with an owned end, labels each component with the smallest label in it, and copies its
//   owned particles' labels to their ghosts on the other ranks; repeated until no ghost's label
//   changed on any rank. Labels only fall, and each bond is known to the owners of both its ends,
//   so at the end a label is constant along every bond and is its component's smallest id.
// * Wall-bridge liquid: the sum of the wall bridges' volumes in the serial run's order (by wall
//   part, then serial slot), added on rank 0 from the non-zero values and broadcast.
#include <cstdint>
#include <vector>

#include "engine/analysis/agglomerates.hpp"
#include "engine/io/h5_series.hpp"
#include "engine/parallel/mpi/mpi_domain.hpp"

namespace drumlab {

struct MpiBondFrame {
  std::vector<std::uint32_t> label;  ///< agglomerate id of each owned particle (local order)
  SeriesBondRows bonds;              ///< this rank's bonds, by row
  std::vector<std::uint64_t> row;    ///< their rows in the frame's bond list (increasing)
  std::uint64_t total = 0;           ///< bonds over all ranks
  double wall_liquid = 0.0;          ///< m^3, the same on every rank
};

/// The frame of `sim` (the local set of `domain`) under the criterion `options`. Collective.
MpiBondFrame mpi_bond_frame(MpiDomain& domain, const Simulation& sim,
                            const AgglomerateOptions& options);

}  // namespace drumlab
