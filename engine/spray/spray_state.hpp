#pragma once
// The evolving state of a scene's binder spray (engine/spray/droplet_cloud.hpp), as plain data
// for checkpoints and restarts: the airborne droplets, each nozzle's counts and the wall's film.
// Everything else about the droplets is a function of the scene and the time.
#include <cstdint>
#include <vector>

#include "engine/types.hpp"

namespace drumlab {

struct Droplet {
  Vec3 position = Vec3::Zero();  ///< m
  Vec3 velocity = Vec3::Zero();  ///< m/s
  std::uint64_t serial = 0;      ///< k: the nozzle's k-th droplet (1-based)
  std::uint32_t spray = 0;       ///< index of its nozzle
};

struct SprayState {
  std::vector<Droplet> droplets;
  /// Per nozzle: droplets emitted, absorbed by particles, lost at the wall, on the (wet) wall.
  std::vector<std::uint64_t> emitted, absorbed, lost, walled;
  /// The wall film's patches (m^3 each; empty: no nozzle wets the wall).
  std::vector<double> wall_film;
  /// No spray: a scene without [[spray]] (or a checkpoint written without one).
  bool empty() const { return emitted.empty(); }
};

}  // namespace drumlab
