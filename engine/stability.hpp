#pragma once
// What stops a run and what the stop says (Simulation::check_stability): the contact with the
// largest overlap, found by Simulation::diagnostics(), and the one-line reasons of UnstableError.
// Every reason names the scene key that changes what it reports or what would cure it.
#include <cstdint>
#include <string>
#include <string_view>

#include "engine/drum.hpp"
#include "engine/particles.hpp"
#include "engine/types.hpp"

namespace drumlab {

class DomainHooks;

/// The contact with the largest overlap / smaller radius: the two bodies and how they move.
struct OverlapSite {
  Index id_a = 0;                      ///< stable id of the particle
  std::int64_t id_b = -1;              ///< stable id of the other particle; -1 for a wall
  WallPart wall = WallPart::cylinder;  ///< the wall part when id_b < 0
  std::int64_t mesh = -1;              ///< a triangle wall's number when id_b < 0 (else -1)
  double radius_a = 0.0;               ///< m
  double radius_b = 0.0;               ///< m (0 for a wall)
  Vec3 point = Vec3::Zero();           ///< contact point (middle of the overlap), m
  double relative_speed = 0.0;         ///< |v_a - v_b|, b the wall surface for a wall, m/s
  double closing_speed = 0.0;          ///< speed of approach along the normal (> 0: closing), m/s

  bool is_wall() const { return id_b < 0; }
};

/// The overlap site of particle i on wall part `part` (its contact c) of a drum turning at omega
/// (rad/s).
OverlapSite wall_site(const Particles& p, std::size_t i, WallPart part, const WallContact& c,
                      double omega);
/// The overlap site of particle i on triangle wall `mesh`: the contact's point on the wall,
/// `normal` into the particle, the wall's surface velocity there `wall_velocity`.
OverlapSite mesh_site(const Particles& p, std::size_t i, std::size_t mesh, const Vec3& normal,
                      double overlap, const Vec3& wall_velocity);
/// The overlap site of particles i and j, dx = x_i - x_j (nearest image).
OverlapSite pair_site(const Particles& p, std::size_t i, std::size_t j, const Vec3& dx);

/// A decomposed run: every rank calls this with its own largest ratio and site and the maximum
/// over all ranks; afterwards every rank holds the site of the rank with that maximum.
void reduce_overlap_site(DomainHooks& domain, double local_ratio, double global_ratio,
                         OverlapSite& site);

/// "time.dt (now 0.0001 s = 0.163 Rayleigh times)": the key to try and its value.
std::string time_step_key(double dt, double rayleigh_time);

/// Why an overlap of `ratio` radii above the limit `max_overlap` (time.max_overlap) stops the
/// run: where, between which bodies, how fast they meet, and what would help.
std::string overlap_reason(const OverlapSite& site, double ratio, double max_overlap, double dt,
                           double rayleigh_time);

/// The one-line error of a run that went unstable at `step` (time t, s), `why` including what
/// to do about it.
UnstableError unstable_error(std::uint64_t step, double t, std::string_view why);

}  // namespace drumlab
