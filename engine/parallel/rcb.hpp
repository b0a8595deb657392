#pragma once
// Recursive coordinate bisection (RCB) of the particles into R boxes, for the MPI domain
// decomposition (issue 15). Each level cuts one box of the tree in two with a plane normal to the
// box's longest extent, as LAMMPS' `balance rcb` does (rcb.cpp chooses the cut dimension as the
// longest one of the box being cut): a deep drum (depth > diameter) is first cut along its axis
// z, a shallow one across it, and every later level again takes the longest side of what is left.
// The R ranks of a box are split into floor(R/2) and the rest, and the cut is placed so that the
// two sides carry the particle count (or work weight) in that proportion: any R >= 1, not only
// powers of two. The boxes tile the domain (every point of it has one owner, so a particle that
// moves stays owned); the cut lies halfway between the last particle of one side and the first of
// the other.
#include <cstddef>
#include <span>
#include <vector>

#include "engine/search/contact_search.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// One box of the cut tree: a leaf is one rank's box; an inner node is cut at `cut` along `axis`
/// into `left` (coordinates below the cut) and `right`.
struct RcbNode {
  Box box;
  int rank_begin = 0;  ///< the node's ranks [rank_begin, rank_end)
  int rank_end = 1;
  int axis = -1;  ///< 0, 1, 2 (x, y, z) for an inner node, -1 for a leaf
  double cut = 0.0;
  int left = -1;  ///< child node indices (inner nodes)
  int right = -1;
  std::size_t count = 0;  ///< particles in the node
  double weight = 0.0;    ///< their summed weight
  bool leaf() const { return axis < 0; }
};

struct Decomposition {
  std::vector<int> owner;            ///< rank of each particle
  std::vector<Box> boxes;            ///< each rank's box; together they tile the domain
  std::vector<RcbNode> nodes;        ///< the cut tree, root first
  std::vector<std::size_t> owned;    ///< particles per rank
  std::vector<double> owned_weight;  ///< summed weight per rank
  int ranks() const { return static_cast<int>(boxes.size()); }
};

/// Decomposes the particles at `position` (inside `domain`) into `ranks` boxes by RCB. `weight`:
/// one positive work weight per particle, or empty for the count (weight 1 each). Throws
/// InputError for ranks < 1 or a weight span of the wrong size.
Decomposition rcb_decompose(std::span<const Vec3> position, std::span<const double> weight,
                            const Box& domain, int ranks);

/// The rank whose box holds x: the cut tree walked from the root (coordinates below a cut go
/// left), so every point has exactly one owner, also outside the domain.
int rcb_owner(const Decomposition& d, const Vec3& x);

/// The drum's bounding box in its own frame, [-D/2, D/2]^2 x [0, depth]: the domain RCB cuts.
Box drum_domain(double diameter, double depth);

}  // namespace drumlab
