#pragma once
// The liquid's migration across MPI ranks (engine/README.md, "Domain decomposition"): a step of
// Simulation::step() between the two passes of the cohesive parts (engine/contact/
// cohesion_loops.hpp), and the replay of every rank's bridge events in the serial run's order.
//
// A bridge event changes two films (a bridge forms: take_from_films reads and takes from both; a
// bridge ruptures: half its volume back to each). The serial pass runs the events one by one by
// increasing pair (i, j), so a film can change several times in a step and an event may need a
// film that an event of another rank changed just before. Each rank lists the events whose first
// particle it owns (listed pairs and dropped pairs alike) and the films its owned particles hold
// before the pass; the lists are gathered on every rank, and every rank replays all events in the
// serial order (BridgeReplay), which gives it each event's films as they stand just before it, and
// each film as the pass leaves it (BridgeEventFilms). The rank's own ordered pass then runs each
// of its events from those films (its force and its pair's state come out as in the serial run)
// and ends with the replay's final films. A serial run has no hooks and runs none of this.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/contact/liquid_bridge.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// One bridge event of this step, by local rows i < j: `volume` > 0: a bridge of that volume
/// ruptures; 0: a bridge forms.
struct BridgeEvent {
  Index i;
  Index j;
  double volume;
};

/// What the replay tells a rank's ordered pass: for each of its events, in the order listed,
/// whether it runs here and the films of i and j just before it; then every local film an event
/// changed, as the serial pass leaves it.
struct BridgeEventFilms {
  struct Before {
    bool run = false;  ///< false: not this rank's to run (a pair of two ghosts, or no event)
    double film_i = 0.0;
    double film_j = 0.0;
  };
  std::vector<Before> before;
  std::vector<std::pair<Index, double>> after;  ///< (local particle, film)
};

/// A rank's side of the replay (films: the kLiquidFilmArray of its local particles).
class BridgeEventHooks {
 public:
  virtual ~BridgeEventHooks() = default;
  /// Replays all ranks' events of this step in the serial order (collective: every rank calls
  /// it, with or without events): `events` this rank's, `film` its films before the ordered
  /// pass. Replaces `out`.
  virtual void replay(const LiquidBridge& bridge, std::span<const BridgeEvent> events,
                      const double* film, BridgeEventFilms& out) = 0;
};

/// A bridge event keyed by the serial slots a < b of its pair, with the films of a and b as the
/// lister holds them (used only for a particle whose owner sent no film).
struct SlotEvent {
  std::uint64_t a = 0, b = 0;
  double volume = 0.0;  ///< > 0: rupture of a bridge of that volume; 0: formation
  double film_a = 0.0, film_b = 0.0;
};
struct SlotFilm {
  std::uint64_t slot = 0;
  double film = 0.0;
};

/// All ranks' events of one step replayed in the serial order.
class BridgeReplay {
 public:
  /// Replays `events` (any order; sorted here by (a, b)) from the films `films` (by their owners;
  /// any order, a slot twice with the same value allowed).
  void run(const LiquidBridge& bridge, std::vector<SlotEvent> events, std::vector<SlotFilm> films);
  /// The films of a and b just before event (a, b); nullptr if (a, b) is no event of this step.
  const std::pair<double, double>* before(std::uint64_t a, std::uint64_t b) const;
  /// Every film an event touched, as the last of them leaves it (by increasing slot).
  const std::vector<SlotFilm>& films() const { return films_; }
  std::size_t size() const { return events_.size(); }

 private:
  std::vector<SlotEvent> events_;
  std::vector<std::pair<double, double>> before_;
  std::vector<SlotFilm> films_;
};

}  // namespace drumlab
