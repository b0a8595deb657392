#pragma once
// Granules as communities of the bond-force network (the `community` granule criterion).
//
// In a dense wet bed every particle is bridged to its neighbours, so the connected components of
// the bridge graph percolate through the bed; Jain et al. 2025 (arXiv 2510.04867) find that
// communities of the network weighted by each bridge's force give granules that follow the fill
// level and the liquid content instead. A community is a set of particles bound more strongly to
// each other than a random network with the same bond strengths would bind them: the partition
// maximising the modularity
//   Q = 1/(2W) sum_ij [w_ij - gamma s_i s_j / (2W)] delta(c_i, c_j),
// w_ij the force of the bond between i and j (N), s_i = sum_j w_ij the strength of particle i,
// W the sum of all bond forces and gamma the resolution (1: Newman-Girvan; larger: smaller
// communities). igraph's Leiden algorithm (Traag, Waltman and van Eck 2019) finds it; its
// communities are connected by bonds, unlike Louvain's.
//
// Reproducible: the network is built in the order of the stable particle ids (not storage order,
// which depends on threads and search method) and igraph's random generator is seeded with a
// fixed seed before each call, so one frame gives one partition on every run. Bonds of zero
// force (a bridge of a liquid without surface tension) carry no weight and join nothing.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/contact/bond.hpp"

namespace drumlab {

/// The community of each particle (storage slots of `id`, the stable ids): for every particle,
/// the storage slot of the member of its community with the smallest stable id (a particle
/// without a bond of positive force is its own). Throws std::invalid_argument for a bond out of
/// range or a resolution that is not positive, std::runtime_error if igraph fails.
std::vector<std::size_t> bond_communities(std::span<const std::uint32_t> id,
                                          std::span<const Bond> bonds, double resolution);

}  // namespace drumlab
