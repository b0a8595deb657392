#pragma once
// The spray's terms of a frame's liquid accounting (m^3), beside the bed's films, bridges and
// wall bridges: sprayed = airborne + absorbed + lost + on the wall, and the absorbed liquid (and
// what particles took from the wall's film) is in the bed, so films + bridges + wall bridges +
// airborne + lost + on_wall - sprayed is the scene's initial liquid at every frame. All zero for
// a scene without [[spray]].
namespace drumlab {

struct SprayLiquid {
  double sprayed = 0.0;   ///< left the nozzles so far
  double airborne = 0.0;  ///< in droplets still flying
  double lost = 0.0;      ///< in droplets that reached the drum wall (at_wall = "lost")
  double on_wall = 0.0;   ///< in the wall's film now (at_wall = "wet": reached it, not yet taken)
  friend bool operator==(const SprayLiquid&, const SprayLiquid&) = default;
};

}  // namespace drumlab
