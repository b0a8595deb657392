#pragma once
// The loops of the cohesive law parts (engine/contact/liquid_bridge.hpp, sjkr_cohesion.hpp), run
// after the contact forces of a scene that has one (a dry scene runs none of this).
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
#include <string_view>
#include <vector>

#include "engine/contact/bond.hpp"
#include "engine/contact/contact_history.hpp"
#include "engine/contact/liquid_bridge.hpp"
#include "engine/contact/sjkr_cohesion.hpp"
#include "engine/drum.hpp"
#include "engine/parallel/bridge_events.hpp"
#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// The cohesive parts of a composed law and where each keeps its scalars in a contact's state.
struct CohesiveParts {
  const LiquidBridge* bridge = nullptr;  ///< nullptr: no liquid
  std::size_t bridge_offset = 0;
  const SjkrCohesion* sjkr = nullptr;  ///< nullptr: no dry adhesion
  std::size_t sjkr_offset = 0;
  bool any() const { return bridge != nullptr || sjkr != nullptr; }
};

/// Scratch of cohesion_pair_loop, reused every step (grows, never shrinks). Block b (rows
/// [b * kCohesionBlockRows, ...)) keeps its entries in entries[row_start[first row] + q] for q <
/// count[b]: every listed pair that changes a particle's force or a film, by increasing (i, j).
struct CohesionBuffers {
  struct Entry {
    Index i;
    Index j;
    std::uint32_t k;  ///< the pair's place in the contact list
    std::uint32_t
        event;   ///< 1: a bridge forms or ruptures (films change): the ordered pass does it
    Vec3 force;  ///< otherwise the force on j (-force on i)
  };
  std::vector<Entry> entries;
  std::vector<std::size_t> count;
  /// touch_mark of every listed pair at this step, written by the contact pair loop (which
  /// computes each listed pair's distance anyway) and read by the cohesive pass.
  std::vector<std::uint8_t> mark;
  /// A decomposed run's ordered pass with liquid migration (engine/parallel/bridge_events.hpp):
  /// nullptr serially. `events`: its scratch, this step's bridge events.
  BridgeEventHooks* hooks = nullptr;
  std::vector<BridgeEventHooks::Event> events;
};

/// A listed pair's touch mark at squared centre distance dist2, radii summing to sum_r:
/// kTouchOrEqual if |d| <= r_i + r_j (a bridge may form, an sjkr contact acts), kApartCentres if
/// the centres differ (|d| > 0: the pair has a direction).
inline constexpr std::uint8_t kTouchOrEqual = 1;
inline constexpr std::uint8_t kApartCentres = 2;
[[gnu::always_inline]] inline std::uint8_t touch_mark(double dist2, double sum_r) {
  return static_cast<std::uint8_t>(static_cast<unsigned>(!(dist2 > sum_r * sum_r)) |
                                   (static_cast<unsigned>(dist2 != 0.0) << 1));
}
inline constexpr std::size_t kCohesionBlockRows = 256;

/// Advances every listed pair's cohesive state by dt (bridges form, age, rupture; films give and
/// take liquid) and adds the attractive forces to p.force. Settles and forgets the dropped pairs.
/// Two passes: (1) in parallel over blocks of rows, every pair whose bridge neither forms nor
/// ruptures gets its force and its state advanced (they read no film); the others are marked;
/// (2) one thread, by increasing (i, j) with the dropped pairs merged in, does the marked pairs'
/// bridge events (liquid migration) and adds every force. The films and the sums of p.force are
/// then made in the same order as by one pass over the pairs, for any thread count.
/// buffers.mark must hold every listed pair's touch_mark at the current positions (the contact
/// pair loop, ContactModel::add_pair_forces, writes it just before).
void cohesion_pair_loop(const CohesiveParts& parts, Particles& p, ContactList& contacts,
                        double period, double dt, CohesionBuffers& buffers);

/// The same for the particles `candidates` (increasing) against the drum wall turning at omega:
/// wall bridges (state in the kWallBridge*Arrays of p) and sjkr with the wall (no state). In
/// parallel over the candidates: a particle's wall bridges change only its own film and force.
void cohesion_wall_loop(const CohesiveParts& parts, Particles& p, std::span<const Index> candidates,
                        const Drum& drum, double omega, double dt);

/// The live links among `contacts`: one Bond per pair with a live bridge or an adhesive
/// (overlapping, k_c > 0) sjkr contact; force = bridge + adhesion at the current state.
void cohesion_bonds(const CohesiveParts& parts, const Particles& p, const ContactList& contacts,
                    double period, std::vector<Bond>& out);

/// The initial split (LiquidConfig::film_share < 1): every touching listed pair gets a bridge from
/// the reserves of both particles (m^3 each, not in their films): each particle's reserve divided
/// equally among its touching pairs, the bridge capped at the maximum volume (both shares scaled
/// down alike); what a particle's reserve does not give goes to its film. Emptied on return.
void seed_bridges(const CohesiveParts& parts, Particles& p, ContactList& contacts, double period,
                  std::vector<double>& reserve);

/// The per-particle arrays the liquid needs (the film with migration, the wall bridges'
/// volume and age per wall part with wall bridges; `wall_parts`: 1 with periodic ends, else 3).
std::vector<std::string_view> liquid_array_names(const LiquidBridge& bridge,
                                                 std::size_t wall_parts);
/// Fills the film array (registered) from the scene's liquid content: film_share of each
/// particle's liquid (content x its solid volume) in its film, the rest in `reserve`
/// (seed_bridges).
void fill_films(const LiquidConfig& liquid, Particles& p, std::vector<double>& reserve);

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

/// Gap (m, negative: overlap) and unit normal (from the wall into the particle) of a sphere
/// against one wall part, also when apart (Drum::contact reports only overlaps).
struct WallGap {
  double gap = 0.0;
  Vec3 normal = Vec3::Zero();
};
WallGap wall_gap(const Drum& drum, WallPart part, const Vec3& x, double r);

}  // namespace drumlab
