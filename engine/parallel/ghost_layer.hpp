#pragma once
// The ghost layer of a decomposition: for each rank, the particles of other ranks that can
// interact with one of its own, i.e. whose centre lies within the interaction reach of its box
// (periodic drum ends: the distance along z is the nearest image's, engine/periodic.hpp). The
// MPI domain (engine/parallel/mpi/mpi_domain.hpp) sends these particles' state to the rank every
// step and uses the same reach.
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "engine/parallel/rcb.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// How far (m) from its box a rank must see another rank's particle of radius r: an owned
/// particle i in the box and a partner j interact when |x_i - x_j| <= r_i + r_j + pair_range +
/// tolerance (the search's test, engine/search/search_input.hpp), and r_i <= r_max, so
///     reach(r_j) = r_j + r_max + pair_range + kTouchTolerance
///                  (+ the Verlet skin, m, when the search keeps a Verlet list: its listed pairs
///                  reach that far, and ghosts then need only change at a rebuild, when particles
///                  migrate).
/// pair_range is ContactModel::max_pair_range() (the search margin: 0 for a dry law, a liquid
/// bridge's rupture distance). A small particle's reach is shorter than a large one's by the
/// difference of their radii (LAMMPS' `comm_modify mode multi` makes the same saving per atom
/// type).
struct GhostReach {
  double beyond = 0.0;  ///< the reach less the particle's own radius: r_max + range + tol + skin
  double max_radius = 0.0;
  double of(double radius) const { return radius + beyond; }
  double largest() const { return of(max_radius); }  ///< 2 r_max + pair_range + tol + skin
};

GhostReach ghost_reach(double max_radius, double pair_range, double verlet_skin);

/// The same for a scene (its search method resolved, not "auto"): r_max of its classes, the pair
/// range of its ContactModel, and performance.verlet_skin x r_min if its search is a Verlet list.
GhostReach ghost_reach(const SceneConfig& scene);

/// Distance (m) from a point to a box (0 inside); with `period_z` the z distance is that of the
/// nearest periodic image (box and point z in [0, period_z)).
double box_distance(const Box& box, const Vec3& x, std::optional<double> period_z);

/// The ranks (ascending, possibly including x's owner) whose box lies within `reach` of x.
void ranks_within(const Decomposition& d, const Vec3& x, double reach,
                  std::optional<double> period_z, std::vector<int>& out);

struct GhostLayer {
  GhostReach reach;
  /// Per rank: the particles (indices) of other ranks within their reach of its box, ascending.
  std::vector<std::vector<Index>> ghosts;
  /// Per rank: the ranks its ghosts come from, ascending (one message each per exchange).
  std::vector<std::vector<int>> sources;
};

/// The ghost layer of `d` for the particles at `position` with `radius` (the ones it decomposed).
/// Walks the cut tree per particle, so its cost grows with the ranks near the particle, not with
/// all R.
GhostLayer ghost_layer(const Decomposition& d, std::span<const Vec3> position,
                       std::span<const double> radius, GhostReach reach,
                       std::optional<double> period_z);

}  // namespace drumlab
