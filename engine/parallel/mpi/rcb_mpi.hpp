#pragma once
// RCB over particles spread over the ranks (issue 15): the cut tree of rcb_decompose
// (engine/parallel/rcb.hpp), found without gathering the positions on any rank. Each level of the
// tree is cut at once: for every box of the level, the weighted median along its longest side is
// narrowed by histograms (128 bins of the coordinate, summed over the ranks) until at most 1024
// particles lie in the bin that holds it; those are gathered, sorted, and the split chosen by
// rcb_decompose's rule. A rank sends O(bins x boxes) numbers per round, whatever its particle
// count.
//
// Same tree as rcb_decompose on all ranks' particles together wherever the coordinates along each
// cut are distinct and the weight sums exact (tests/mpi_checks/rcb_check.cpp); with equal
// coordinates at a cut, its children are the particles below the cut and the rest, as rcb_owner
// assigns them, where the serial cut takes an arbitrary k of them. Every rank gets the same tree:
// counts are summed exactly, weights by MpiComm::agreed_sum. A particle at a non-finite position (a
// run blowing up between its stability checks) counts in its box but never places a cut; it goes
// where rcb_owner sends it, and the next stability check stops the run.
#include <span>

#include "engine/parallel/mpi/mpi_comm.hpp"
#include "engine/parallel/rcb.hpp"

namespace drumlab {

/// The decomposition of every rank's particles (`position`, and one positive `weight` each, or
/// empty on every rank for the count) into comm.size() boxes of `domain`. Collective. `owner`
/// holds this rank's particles' ranks; boxes, nodes, owned and owned_weight are the whole tree's,
/// the same on every rank.
Decomposition rcb_decompose_mpi(MpiComm& comm, std::span<const Vec3> position,
                                std::span<const double> weight, const Box& domain);

}  // namespace drumlab
