#pragma once
// The partners a Verlet list needs for the particles that moved, without rebuilding it for all.
//
// A list built at reference positions ref holds every pair with |ref_i - ref_j| <= pair_cutoff(r_i,
// r_j, margin + skin) (search_input.hpp: with the touching tolerance). No pair outside it can come
// within the margin while the two largest displacements from ref sum to at most the skin, since
// |x_i - x_j| >= |ref_i - ref_j| - |x_i - ref_i| - |x_j - ref_j|. That holds for each pair's own
// reference positions, so the list stays valid if a few particles take their current position as
// their new reference, as long as every pair of one of them within that cut-off of the new
// references is added (and their old pairs beyond that cut-off at the new references dropped: such
// a pair does not touch). In a drum the rebuilds are set by the fastest few particles (a flowing
// layer over a bed that turns with the wall); patching those few costs a grid of the references and
// a merge, not the whole search.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/search/contact_search.hpp"
#include "engine/search/search_input.hpp"

namespace drumlab {

class VerletPatch {
 public:
  /// Sets `out` to every pair (min, max) with one particle of `moved` and |ref_a - ref_b| <=
  /// pair_cutoff(r_a, r_b, margin) (minimum image along z when period > 0), sorted by (i, j),
  /// each once.
  /// `moved`: indices into ref and radius, ascending.
  void find(std::span<const Vec3> ref, std::span<const double> radius, std::span<const Index> moved,
            double margin, double period, std::vector<IndexPair>& out);

 private:
  /// A reference and its radius, as the visits read them.
  struct PackedSphere {
    double x, y, z, r;
  };
  std::vector<std::uint32_t> cell_of_;  ///< each particle's cell
  std::vector<std::uint32_t> fill_;     ///< the counting sort's counts (cell ends)
  std::vector<Index> members_;          ///< particles by cell
  std::vector<PackedSphere> sorted_;    ///< their references and radii, by cell
  PairSlices slices_;                   ///< the pairs each share of the moved particles found
  std::vector<IndexPair> scratch_;      ///< the pair sort's scratch
  std::vector<std::uint32_t> counts_;
};

}  // namespace drumlab
