#include "engine/memory_estimate.hpp"

#include <fmt/format.h>

#include "engine/contact/contact_model.hpp"
#include "engine/search/cell_index.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/search/verlet_list.hpp"

namespace drumlab {

namespace {

constexpr double kVec3 = sizeof(Vec3);
constexpr double kIndex = sizeof(Index);
constexpr double kSize = sizeof(std::size_t);
constexpr double kPair = sizeof(IndexPair);
/// A pair array holds about this much more than it uses: its capacity follows the most pairs it
/// ever held, and push_back doubles it.
constexpr double kGrowth = 1.5;
/// The renumbering's scratch and the pair loop's buffers grow by a quarter (vector_room.hpp; the
/// contact list's arrays too, but the estimate keeps kGrowth for them: it also stands for what it
/// does not count in detail, such as the grids' fixed tables).
constexpr double kRoom = 1.25;

/// Bytes per particle of the search structures of one grid (no Verlet list).
double grid_bytes_per_particle(const SearchMethodInfo& m, double pairs) {
  const double counters = 2.0 * sizeof(std::uint32_t);  // cells visited, pairs tested
  const double found = kGrowth * kPair * pairs;         // the pairs of one call, per thread
  switch (m.cell) {
    case CellRule::none:
      return counters + found;
    case CellRule::min_radius:
    case CellRule::max_radius:  // slot cell, order, sorted position and radius, scratch
      return counters + found + sizeof(CellCoord) + kIndex + kVec3 + sizeof(double) +
             sizeof(std::uint32_t);
    case CellRule::per_level:  // the same per level member, plus three sort buffers
      return counters + found + 2.0 * sizeof(CellCoord) + 2.0 * kIndex + kVec3 + sizeof(double) +
             kSize;
  }
  return counters + found;
}

}  // namespace

MemoryEstimate estimate_memory(std::string_view method, const MemoryShape& s) {
  const auto parsed = parse_search_method(method);
  if (!parsed) {
    throw InputError(fmt::format("memory estimate: unknown search method '{}'", method));
  }
  const double pairs = s.listed_pairs_per_particle;
  double b = 0.0;
  // Particles: position, velocity, omega, force, torque; radius, mass, 1/m, 1/I; class; id.
  b += 5.0 * kVec3 + 4.0 * sizeof(double) + sizeof(std::uint8_t) + kIndex;
  b += 2.0 * kWallParts * kVec3;  // wall history, and its scratch for re-ordering
  // Contact list: rows (current, previous, fill), and per pair partner and history, twice
  // (current and previous, for the history transfer), and its row (the pair loop's index).
  b += 3.0 * kSize + kGrowth * pairs * (2.0 * (kIndex + kVec3) + kIndex);
  // The pair loop's cross-block sums (one thread).
  b += s.rotation ? 2.0 * kVec3 : kVec3;
  // Re-ordering: Morton keys, order and inverse, one scratch array of each type; renumbering
  // the contacts keeps two arrays per pair.
  if (s.reorder) {
    b += sizeof(std::uint64_t) + 3.0 * kIndex + kVec3 + sizeof(double) + sizeof(std::uint8_t) +
         kIndex;
    b += kRoom * pairs * (kPair + kSize);
  }
  // From two threads on, the parallel pair loop (contact/contact_model.cpp) keeps per pair a
  // force slot, the force and the partner's torque, and the pair's row; per particle its
  // block's end. Measured (tests/unit/test_memory_estimate.cpp, 2026-12-07): 38-43 B a particle
  // more on the grids, 335-350 with a Verlet list.
  if (s.threads > 1) {
    b += kRoom * pairs * (sizeof(std::uint32_t) + kVec3 + (s.rotation ? kVec3 : 0.0) + kIndex) +
         kSize;
  }
  // Wall candidates: flags, positions at the build and scratch, the list.
  b += sizeof(std::uint8_t) + 2.0 * kVec3 + kIndex;
  if (parsed->verlet) {
    // The list and its scratch, positions and radii at the build and their scratch, counts;
    // the builder's own structures.
    b += 2.0 * kGrowth * kPair * pairs + 2.0 * (kVec3 + sizeof(double)) +
         2.0 * sizeof(std::uint32_t);
    b += grid_bytes_per_particle(*parsed->method, pairs);
    // From 4096 particles on, the patch's grid (search/verlet_patch.hpp): each particle's cell,
    // the members by cell with their references and radii, and about two cells a particle of
    // counts per thread.
    if (s.particles >= VerletListSearch::kPatchMinParticles) {
      b += 2.0 * kIndex + 4.0 * sizeof(double) + 2.0 * s.threads * sizeof(std::uint32_t);
    }
  } else {
    b += kGrowth * kPair * pairs;  // the simulation's pair list
    b += grid_bytes_per_particle(*parsed->method, pairs);
  }
  MemoryEstimate e;
  e.per_particle = b;
  e.particles = static_cast<double>(s.particles);
  e.grid = s.grid_cells * sizeof(CellRange);
  return e;
}

double settled_pairs_per_particle(bool verlet, double skin) {
  // Each pair is stored once: half the coordination number. Measured in the demo drum's rolling
  // bed (3 sizes, 18,825 particles): 32,905 contacts = 1.75 per particle, and 3.82 listed pairs
  // per particle with a Verlet skin of 0.5 R_min (the formula below gives 2 x 1.95 = 3.9).
  const double touching = 2.0;
  if (!verlet) return touching;
  // Neighbours within 2 r + skin r of a centre, in a bed of equal spheres: the count grows with
  // the volume of that shell.
  const double reach = 1.0 + 0.5 * skin;
  return touching * reach * reach * reach;
}

}  // namespace drumlab
