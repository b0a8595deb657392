#pragma once
// The spray's terms of a frame's liquid accounting (m^3), beside the bed's films, bridges and
// wall bridges: sprayed = airborne + absorbed + lost, and the absorbed liquid is in the bed, so
// films + bridges + wall bridges + airborne + lost - sprayed is the scene's initial liquid at
// every frame. All zero for a scene without [[spray]].
namespace drumlab {

struct SprayLiquid {
  double sprayed = 0.0;   ///< left the nozzles so far
  double airborne = 0.0;  ///< in droplets still flying
  double lost = 0.0;      ///< in droplets that reached the drum wall
  friend bool operator==(const SprayLiquid&, const SprayLiquid&) = default;
};

}  // namespace drumlab
