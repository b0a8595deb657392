#include "engine/drum_orbit.hpp"

#include <cmath>

namespace drumlab {

double carrier_field(const DrumOrbit& orbit) {
  return orbit.omega * orbit.omega * orbit.radius;
}

double speed_ratio(const DrumConfig& drum) {
  return drum.omega / drum.orbit.omega - 1.0;
}

double critical_speed_ratio(const DrumOrbit& orbit, double rho) {
  return std::sqrt(orbit.radius / rho);
}

PlanetaryRegime predicted_regime(const DrumConfig& drum, double r_min, double r_max) {
  const double r = 0.5 * drum.diameter;
  const double ratio = std::abs(1.0 + speed_ratio(drum));
  if (ratio >= critical_speed_ratio(drum.orbit, r - r_max)) return PlanetaryRegime::held;
  if (ratio >= critical_speed_ratio(drum.orbit, r - r_min)) return PlanetaryRegime::partly_held;
  return PlanetaryRegime::released;
}

std::string regime_text(PlanetaryRegime regime) {
  switch (regime) {
    case PlanetaryRegime::held:
      return "centrifuging: the wall holds every particle all the way round";
    case PlanetaryRegime::partly_held:
      return "the wall holds the smaller particles all the way round and releases the larger";
    case PlanetaryRegime::released:
      break;
  }
  return "below the critical ratio: the wall releases particles near the point nearest the "
         "central axis (cascading or cataracting)";
}

}  // namespace drumlab
