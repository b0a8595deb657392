#pragma once
// The loops of the cohesive law parts (cohesive_part.hpp; registered in cohesive_laws.hpp), run
// after the contact forces of a scene that has one (a dry scene runs none of this). They are
// generic over the parts: no loop names a law.
//
// One thread, by increasing (i, j) (particles by increasing slot, then wall part): liquid
// migration reads and writes the films of both particles of a pair, so the result depends on the
// order in which the pairs are visited; this fixed order makes it independent of the thread count.
// Pairs the contact list dropped since the last step (ContactList::dropped(), beyond every
// bridge's rupture distance) are settled in the same (i, j) order, merged with the listed ones,
// so every search method (whatever extra pairs it lists within its skin) makes the same changes
// to the films in the same order.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/contact/bond.hpp"
#include "engine/contact/cohesive_laws.hpp"
#include "engine/contact/contact_history.hpp"
#include "engine/contact/liquid_rupture.hpp"
#include "engine/contact/touch_sift.hpp"
#include "engine/drum.hpp"
#include "engine/parallel/bridge_events.hpp"
#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// Scratch of the cohesive passes (cohesion_pass_one, cohesion_ordered_pass), reused every step
/// (grows, never shrinks). Block b (rows [b * kCohesionBlockRows, ...)) keeps its entries in
/// entries[row_start[first row] + q] for q < count[b]: every listed pair that changes a particle's
/// force or a film, by increasing (i, j).
struct CohesionBuffers {
  struct Entry {
    Index i;
    Index j;
    std::uint32_t k;      ///< the pair's place in the contact list
    std::uint32_t event;  ///< 1: a part's event (films change): the ordered pass does it
    Vec3 force;           ///< otherwise the force on j (-force on i)
  };
  std::vector<Entry> entries;
  std::vector<std::size_t> count;
  /// touch_mark of every listed pair at this step, written by the contact pair loop (which
  /// computes each listed pair's distance anyway) and read by the cohesive pass.
  std::vector<std::uint8_t> mark;
  /// This step's events (pass 1 lists them when asked: a decomposed run with liquid migration
  /// replays them across the ranks, parallel/bridge_events.hpp): the marked listed pairs by
  /// increasing (i, j), then the dropped pairs that a part with events settles.
  std::vector<BridgeEvent> events;
  /// Scratch of the ordered pass's rupture sharing ([liquid] rupture_to_bridges,
  /// liquid_rupture.hpp).
  mutable RuptureScratch rupture;
};

inline constexpr std::size_t kCohesionBlockRows = 256;

/// The live bridges of overlapping pairs, whose pull the contact pair loop adds (a scene whose only
/// cohesive part is the plain liquid bridge, the part pass 1 runs in BridgeBatch): touching, a
/// bridge pulls with the constant F0 and has no event (it forms on contact and ruptures apart), so
/// the pair loop, which has the pair's separation and radii in its batch anyway, adds F0 to the
/// contact's force and ages the bridge by dt (add_touching_pull, bridge_batch.hpp); pass 1 leaves
/// these pairs out (their touch mark has kOverlapping). state == nullptr: none (every other
/// composition of parts: pass 1 evaluates every acting pair).
struct TouchingPull {
  double* state = nullptr;  ///< the bridge's scalars of listed pair k: state[k * stride]
  std::size_t stride = 0;
  double f0_per_radius = 0.0;  ///< BridgeLiquid::f0_per_radius of the pair liquid
  double dt = 0.0;             ///< the bridges' age step
};
TouchingPull touching_pull(const CohesiveParts& parts, ContactList& contacts, double dt);

/// Advances every listed pair's cohesive state by dt (each part's advance_pair: bridges form, age,
/// rupture; films give and take liquid) and adds the attractive forces to p.force, in two passes.
/// buffers.mark must hold every listed pair's touch_mark at the current positions and `contacts`
/// its entry_rows() (the contact pair loop, ContactModel::add_pair_forces_parallel, writes and
/// indexes them just before).
/// Pass 1, in parallel over blocks of rows: every pair on which a part may act and no part has an
/// event gets its force and its state advanced (they read no film); the others are marked. The
/// pairs of touching_pull() are left out: the pair loop has done them.
/// `list_events`: buffers.events lists this step's events for a replay across MPI ranks.
void cohesion_pass_one(const CohesiveParts& parts, const Particles& p, ContactList& contacts,
                       double period, double dt, CohesionBuffers& buffers, bool list_events);
/// Pass 2, one thread, by increasing (i, j) with the dropped pairs merged in: the marked pairs
/// (events: liquid migration) and every force added; the dropped pairs settled (each part's drop)
/// and forgotten. The films and the sums of p.force are then made in the same order as by one
/// pass over the pairs, for any thread count. `replay` (a decomposed run, nullptr serially): the
/// films each listed event sees and whether it runs here; its final films written at the end.
void cohesion_ordered_pass(const CohesiveParts& parts, Particles& p, ContactList& contacts,
                           double period, double dt, const CohesionBuffers& buffers,
                           const BridgeEventFilms* replay);

/// The same for the particles `candidates` (increasing) against the drum wall turning at omega
/// (each part's advance_wall; its state in p's arrays), each against the wall parts of its
/// `near_parts` bits (empty: all; a part beyond them holds no link, WallCandidates::parts). In
/// parallel over the candidates: a particle's wall state changes only its own film and force.
void cohesion_wall_loop(const CohesiveParts& parts, Particles& p, std::span<const Index> candidates,
                        std::span<const std::uint8_t> near_parts, const Drum& drum, double omega,
                        double dt);

/// The live links among `contacts`: one Bond per pair that some part says is bonded (a live
/// bridge, an adhesive contact); its shares added in the parts' order, the age the first part's.
void cohesion_bonds(const CohesiveParts& parts, const Particles& p, const ContactList& contacts,
                    double period, std::vector<Bond>& out);

/// Liquid held (m^3): in films, in particle-particle bridges, in wall bridges.
struct LiquidTotals {
  double films = 0.0;
  double bridges = 0.0;
  double wall_bridges = 0.0;
  std::size_t bridge_count = 0;
  std::size_t wall_bridge_count = 0;
  double total() const { return films + bridges + wall_bridges; }
};
/// `ghost` (a decomposed run's mask, empty: none): particles, and pairs in their rows, skipped.
LiquidTotals liquid_totals(const CohesiveParts& parts, const Particles& p,
                           const ContactList& contacts, std::span<const std::uint8_t> ghost = {});
/// Liquid held in wall bridges (m^3): the sum of p's kWallBridgeVolumeArrays (0 without them).
double wall_bridge_liquid(const Particles& p, std::span<const std::uint8_t> ghost = {});

}  // namespace drumlab
