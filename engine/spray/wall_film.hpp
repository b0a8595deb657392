#pragma once
// Binder on the drum wall ([[spray]] at_wall = "wet"): droplets that reach the wall leave their
// liquid where they land, the wall carries it round as it turns, and particles that touch the
// wetted place take it up into their films, from where it forms bridges as any film does.
//
// The wall is cut into patches fixed in the drum's own (turning) frame, about one largest
// particle diameter on a side: the mantle in n_theta angular by n_z axial patches, each cap
// (closed ends only) in rings of that width, each ring in the mantle's n_theta sectors. A droplet
// adds its volume to the patch under the point where it reached the wall. Every step, each
// particle touching a wall part (overlap >= 0) takes from the patch under its contact point the
// share min(1, pi r^2 / A) of what that patch holds (r its radius, A the patch's area: the part
// of the patch its footprint wipes), so a particle resting on a wet patch takes it all within a
// few steps and one rolling past takes a share. Particles touching the same patch in one step take
// in the order of their ids, so the films do not depend on the storage order, the thread count or
// the search method. Without a wet patch the pass costs one comparison.
//
// The model is this one's own: MercuryDPM's DropletBoundary either removes droplets at walls or
// lets them bounce off; it has no wall film to compare with.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/drum.hpp"

namespace drumlab {

class WallFilm {
 public:
  /// Patches about `side` (m, > 0) wide on the wall of `drum`. A patch left with less than
  /// `residue` (m^3, >= 0) after a particle's share is taken gives that rest too, so the film does
  /// not linger as ever smaller traces.
  WallFilm(const Drum& drum, double side, double residue);

  std::size_t size() const { return volume_.size(); }
  /// The patch under the wall point nearest `x` on `part`, with the drum turned by `angle` (rad).
  std::size_t patch(WallPart part, const Vec3& x, double angle) const;
  /// The area of patch k (m^2).
  double area(std::size_t k) const;
  /// Adds liquid volume v (m^3) where a droplet at x reached the wall part nearest to it.
  void deposit(const Vec3& x, double angle, double v);
  /// Particles touching the wall take their shares of the patches under them into `film` (as the
  /// header says). Returns the volume taken (m^3).
  double wipe(double angle, std::span<const Vec3> position, std::span<const double> radius,
              std::span<const std::uint32_t> id, std::span<double> film);

  /// The liquid on the wall now (m^3), the sum over patches.
  double volume() const;
  std::span<const double> patches() const { return volume_; }
  /// Restores the patches' volumes (restart). Throws InputError for the wrong count or a
  /// negative or non-finite volume.
  void restore(std::vector<double> volume);

 private:
  Drum drum_;
  std::int64_t n_theta_ = 1, n_z_ = 1, n_ring_ = 0;
  double residue_ = 0.0;
  std::vector<double> volume_;
  std::size_t wet_ = 0;  ///< patches holding liquid
  struct Touch {
    std::size_t patch;
    std::uint32_t id;
    std::uint32_t index;
  };
  std::vector<Touch> touches_;  ///< scratch of wipe
};

}  // namespace drumlab
