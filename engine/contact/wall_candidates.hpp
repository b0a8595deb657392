#pragma once
// The particles that can touch the drum wall: a Verlet list for the wall. The wall loop visits
// only these (the outer layer of the bed) instead of testing every particle against the cylinder
// and both caps every step. The wall is a surface of revolution with flat ends, so its shape does
// not change as the drum turns, and a particle's gap to it changes by no more than the particle
// moves: a particle whose gap to every wall part exceeded `reach` at the last build, and that has
// moved by at most `reach` since, cannot touch the wall.
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "engine/contact/contact_model.hpp"
#include "engine/drum.hpp"
#include "engine/particles.hpp"

namespace drumlab {

class WallCandidates {
 public:
  /// Rebuilds the list if this is the first call, the particle count or `reach` (m, > 0) changed,
  /// or a particle moved by more than `reach` since the last build (in x, y only for periodic
  /// ends, where z does not matter). On a rebuild, the wall history of every particle left out is
  /// zeroed: it does not touch the wall. Returns true if it rebuilt. `moved`: an upper bound on
  /// how far any particle moved since the previous call (m), or infinite if not known; while the
  /// bounds since the last check sum to at most `reach`, no particle is checked.
  bool refresh(const Particles& p, const Drum& drum, double reach, WallHistory& history,
               double moved = std::numeric_limits<double>::infinity());
  /// The candidates, increasing.
  std::span<const Index> list() const { return list_; }
  /// For each candidate (list()[k]), the wall parts it can touch: bit w set where its gap to part
  /// w (WallPart) was within `reach` at the last build. A part's gap changes by no more than the
  /// particle moves too, so the wall loops skip the others (their history was zeroed then).
  std::span<const std::uint8_t> parts() const { return parts_; }
  /// Follows a re-ordering of the particles (slot k now holds the particle that was at order[k];
  /// particle i moved to new_index[i]): the list stays valid without a rebuild.
  void renumber(std::span<const Index> order, std::span<const Index> new_index);
  /// Forces a rebuild at the next refresh.
  void invalidate() { reference_.clear(); }
  std::uint64_t rebuilds() const { return rebuilds_; }
  /// Calls that measured every particle's displacement.
  std::uint64_t checks() const { return checks_; }

 private:
  bool needs_rebuild(const Particles& p, const Drum& drum, double reach);

  std::vector<Index> list_;
  std::vector<std::uint8_t> parts_;
  std::vector<std::uint8_t> keep_;  ///< scratch of a rebuild: the parts particle i can touch
  std::vector<std::pair<Index, std::uint8_t>> scratch_pairs_;  ///< of renumber
  std::vector<Vec3> reference_;                                ///< positions at the last build
  std::vector<Vec3> scratch_;
  double reach_ = 0.0;
  /// Bound on the largest displacement since the last build (m): the measured one after a check,
  /// plus the callers' bounds since.
  double moved_ = std::numeric_limits<double>::infinity();
  std::uint64_t rebuilds_ = 0, checks_ = 0;
};

}  // namespace drumlab
