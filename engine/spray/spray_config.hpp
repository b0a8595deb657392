#pragma once
// One nozzle of binder ([[spray]] in a scene): where it sits, where it points, how its droplets
// leave it and how much liquid it adds when. engine/spray/droplet_cloud.hpp flies the droplets.
// Coordinates are the engine's drum frame (axis along z from 0 to the depth, gravity as the
// scene gives it); the nozzle does not turn with the drum.
#include <limits>
#include <string>

#include "engine/types.hpp"

namespace drumlab {

enum class SprayShape { cone, flat_fan };

/// What becomes of a droplet that reaches the drum wall: lost from the process (MercuryDPM's
/// DropletBoundary removeDropletsAtWalls), or a film on the wall that turns with the drum and
/// that particles touching it take up (engine/spray/wall_film.hpp).
enum class SprayAtWall { lost, wet };

struct SprayConfig {
  std::string name;
  Vec3 position = Vec3::Zero();           ///< nozzle (m), inside the drum
  Vec3 direction = Vec3(0.0, -1.0, 0.0);  ///< the spray's axis (normalised when read)
  SprayShape shape = SprayShape::cone;
  double angle_deg = 20.0;  ///< full opening angle of the cone or of the fan, degrees, [0, 180)
  /// Flat fan: the direction the fan opens along (its part normal to `direction` is used).
  Vec3 fan_axis = Vec3(0.0, 0.0, 1.0);
  double rate = 0.0;   ///< liquid volume per second (m^3/s), >= 0
  double start = 0.0;  ///< s of the simulation clock
  double stop = std::numeric_limits<double>::infinity();  ///< s, > start
  double droplet_radius = 0.0;                            ///< m, > 0
  double droplet_speed = 0.0;                             ///< m/s at the nozzle, >= 0
  SprayAtWall at_wall = SprayAtWall::lost;

  friend bool operator==(const SprayConfig&, const SprayConfig&) = default;
};

}  // namespace drumlab
