#pragma once
// MercuryDPM's rupture with a distribution coefficient ([liquid] rupture_to_bridges = c > 0;
// Kernel/Interactions/AdhesiveForceInteractions/LiquidMigrationWilletInteraction.cc, rupture()):
// a ruptured bridge of volume V gives each of its particles V/2; of that, the share c goes to the
// particle's other live particle-particle bridges (c V/2 / n to each of its n, each topped at
// V_max with the excess to the particle's film) and the rest to its film; a particle without
// another live bridge takes its whole half into its film. Wall bridges are not among the "other
// bridges" (the peer's drum has none).
//
// It needs a particle's other contacts, which no single pair holds, so the ordered pass of the
// cohesive parts (cohesion_loops.cpp) runs it, one thread, by increasing (i, j): the same
// additions in the same order for any thread count and any search method (a listed pair without
// a bridge is not a bridge). Order: particle i's half, then j's; within one half, the film's
// share first, then the bridges by increasing partner slot, each excess added to the film as it
// comes. Not on a decomposed (MPI) run: the replay of bridge events across ranks
// (parallel/bridge_events.hpp) knows films, not the other bridges (the pass refuses it).
#include <cstddef>
#include <vector>

#include "engine/contact/cohesive_laws.hpp"
#include "engine/contact/contact_history.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// Scratch of RuptureSharing, kept between steps (grows, never shrinks): for each particle, the
/// listed pairs k in which it is the partner (col()[k]), by increasing row.
struct RuptureScratch {
  std::vector<std::size_t> start;
  std::vector<std::size_t> next;
  std::vector<std::size_t> k;
};

class RuptureSharing {
 public:
  /// Active if the scene's liquid bridge has rupture_to_bridges > 0 (and films: migration).
  RuptureSharing(const CohesiveParts& parts, ContactList& contacts, double* film,
                 RuptureScratch& scratch);
  bool active() const { return law_ != nullptr; }
  /// Listed pair k = (i, j) at surface gap `gap`, before the parts advance it: if its bridge
  /// ruptures now, its state is emptied and its liquid shared (the part then sees no bridge).
  void listed(std::size_t k, Index i, Index j, double gap);
  /// A dropped pair's bridge of volume v (the list no longer holds it) shared.
  void dropped(Index i, Index j, double v);

 private:
  void share(Index a, double half);
  template <class F>
  void for_each_bridge(Index a, F&& f);
  void index();

  const LiquidBridge* law_ = nullptr;
  std::size_t offset_ = 0;
  ContactList& contacts_;
  double* film_;
  RuptureScratch& scratch_;
  bool indexed_ = false;
};

}  // namespace drumlab
