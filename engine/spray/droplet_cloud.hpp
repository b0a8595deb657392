#pragma once
// Binder droplets between the nozzles ([[spray]], spray_config.hpp) and the bed. Droplets are not
// particles: they never enter the contact search, carry no force and feel only gravity. Each
// step they fly ballistically (exact for constant gravity); a droplet whose path touches a
// particle is absorbed into that particle's liquid film (the first one along its path), one that
// reaches the drum wall is lost, or with at_wall = "wet" joins the wall's film (wall_film.hpp),
// which particles touching the wall take up. MercuryDPM's DropletBoundary is the design this
// follows (its droplets are also massless tracers absorbed by the first particle they touch).
//
// Emission is a function of time alone: nozzle s has emitted floor(Q (t - start) / V) droplets by
// time t (Q its rate, V = 4/3 pi r_d^3, t clipped to [start, stop]); droplet k leaves at
// t_k = start + k V / Q and flies t - t_k in the step it is born. Its direction is drawn from a
// counter-based generator of (nozzle, k): uniform over the cone's solid angle, or uniform in angle
// across a flat fan. So the droplets do not depend on the step size's history, the thread count
// or the search method, and a restart that brings the airborne droplets and the emitted counts
// continues bit for bit.
//
// Liquid accounting (volumes, m^3): sprayed = airborne + absorbed + lost + walled, each a count of
// droplets times V per nozzle; absorbed liquid is in the films (and from there in bridges), the
// walled liquid is on the wall or, once particles took it, in the films too.
#include <cstdint>
#include <span>
#include <vector>

#include <memory>

#include "engine/drum.hpp"
#include "engine/spray/spray_config.hpp"
#include "engine/spray/spray_state.hpp"
#include "engine/spray/wall_film.hpp"

namespace drumlab {

/// Volumes (m^3) and counts of the liquid the nozzles have sprayed so far.
struct SprayTotals {
  double sprayed = 0.0;
  double airborne = 0.0;
  double absorbed = 0.0;  ///< into particles' films
  double lost = 0.0;      ///< reached the drum wall (at_wall = "lost")
  double walled = 0.0;    ///< reached the drum wall (at_wall = "wet"): on it or taken from it
  double on_wall = 0.0;   ///< on the wall's film now
  double taken_from_wall = 0.0;  ///< walled - on_wall: taken into particles' films so far
  std::uint64_t emitted_count = 0, absorbed_count = 0, lost_count = 0, walled_count = 0;
};

/// What one advance did (for a caller that keeps per-step statistics).
struct SprayStep {
  std::uint64_t emitted = 0, absorbed = 0, lost = 0, walled = 0;
  double taken_from_wall = 0.0;  ///< m^3
};

class DropletCloud {
 public:
  /// Throws InputError for a nozzle whose droplet volume is not positive.
  /// `patch` (m): the side of the wall film's patches (the scene's largest particle diameter),
  /// needed (> 0) by a nozzle with at_wall = "wet".
  DropletCloud(std::vector<SprayConfig> sprays, const Drum& drum, const Vec3& gravity,
               double patch = 0.0);

  /// Advances the droplets from t to t + dt: emits the droplets born in it, flies every droplet
  /// and absorbs those whose path touches a particle (positions, radii, stable ids, storage order)
  /// into `film` (m^3 per particle, same order), or loses those that reach the wall (or wets it);
  /// then the particles touching a wet wall take their shares. `angle` is the drum's angle at
  /// t + dt (rad; where the wall's film has turned to). The bed is taken as still during the
  /// step. Serial and ordered: the same films for any thread count.
  SprayStep advance(double t, double dt, std::span<const Vec3> position,
                    std::span<const double> radius, std::span<const std::uint32_t> id,
                    std::span<double> film, double angle = 0.0);

  /// Whether any nozzle can still emit at or after time t, or droplets are airborne.
  bool active(double t) const;
  std::span<const Droplet> droplets() const { return droplets_; }
  const std::vector<SprayConfig>& sprays() const { return sprays_; }
  SprayTotals totals() const;
  /// Droplets emitted by nozzle s so far.
  std::uint64_t emitted(std::size_t s) const { return emitted_[s]; }
  /// One droplet's volume of nozzle s (m^3).
  double droplet_volume(std::size_t s) const { return volume_[s]; }

  /// The direction of nozzle s's k-th droplet (unit vector): the spray's law of directions.
  Vec3 droplet_direction(std::size_t s, std::uint64_t k) const;
  /// Droplets nozzle s has emitted by time t (floor of the sprayed volume over one droplet's).
  std::uint64_t emitted_by(std::size_t s, double t) const;

  /// Restores the evolving state (restart): the airborne droplets, each nozzle's emitted,
  /// absorbed, lost and walled counts (empty: none walled) and the wall film's patches (empty:
  /// a dry wall). Throws InputError if they do not fit the nozzles or the wall.
  void restore(std::vector<Droplet> droplets, std::vector<std::uint64_t> emitted,
               std::vector<std::uint64_t> absorbed, std::vector<std::uint64_t> lost,
               std::vector<std::uint64_t> walled = {}, std::vector<double> wall_film = {});
  /// The evolving state as plain data, and back (restore's checks).
  SprayState state() const;
  void restore(SprayState state);
  std::span<const std::uint64_t> absorbed_counts() const { return absorbed_; }
  std::span<const std::uint64_t> lost_counts() const { return lost_; }
  std::span<const std::uint64_t> walled_counts() const { return walled_; }
  /// The wall's film (a nozzle with at_wall = "wet"); null without.
  const WallFilm* wall_film() const { return wall_film_.get(); }

 private:
  /// Flies the airborne droplets over the step; absorbs, loses or walls them.
  void fly(std::span<const Vec3> position, std::span<const double> radius,
           std::span<const std::uint32_t> id, std::span<double> film, double angle,
           SprayStep& step);
  /// Bins the particles near the droplets' paths of this step into cells of side `cell`.
  void bin_particles(std::span<const Vec3> position, double cell, const Vec3& low,
                     const Vec3& high);
  /// The first particle (smallest path fraction, then smallest id) the chord a -> b of a droplet
  /// of radius rd touches; -1 if none.
  std::int64_t first_hit(const Vec3& a, const Vec3& b, double rd, std::span<const Vec3> position,
                         std::span<const double> radius, std::span<const std::uint32_t> id) const;

  std::vector<SprayConfig> sprays_;
  Drum drum_;
  Vec3 gravity_;
  std::vector<double> volume_;
  std::vector<std::uint64_t> emitted_, absorbed_, lost_, walled_;
  std::unique_ptr<WallFilm> wall_film_;
  std::vector<Droplet> droplets_;
  std::vector<Droplet> kept_;   ///< scratch of advance
  std::vector<Vec3> start_;     ///< scratch: each droplet's position at the start of its flight
  std::vector<double> flight_;  ///< scratch: the time each droplet flies in this step
  // The particle bins of one advance.
  Vec3 low_ = Vec3::Zero();
  double cell_ = 0.0;
  std::int64_t nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<std::uint32_t> cell_start_, cell_items_, cell_fill_;
  std::vector<std::int64_t> cell_of_;
};

}  // namespace drumlab
