#pragma once
// What a planetary drum's carrier ([drum.orbit], scene_config.hpp DrumOrbit) does to the bed,
// in closed form, for `info`, the tests and the regime map.
//
// In the frame that translates with the drum's centre c(t) (|c| = R_o, turning at Omega about the
// central axis) without turning, every particle feels gravity plus the uniform field
// -c'' = Omega^2 c: magnitude Omega^2 R_o, pointing from the central axis through the drum's
// centre, turning with the carrier arm. The wall turns at omega = Omega (1 + k) in that frame.
// A ball carried by the wall (its centre on a circle of radius rho = R - r about the drum's
// centre, moving with the wall) needs the inward force m omega^2 rho; the wall's push N and the
// field's radial part supply it: N = m (omega^2 rho + Omega^2 (c . e)), e the unit vector from
// the drum's centre to the ball. N is least where e points at the central axis (c . e = -R_o),
// so the wall holds the ball all the way round while omega^2 rho >= Omega^2 R_o, i.e.
//     |1 + k| >= sqrt(R_o / rho)     (gravity neglected against Omega^2 R_o),
// and below that the ball leaves the wall near the point nearest the central axis.
#include <string>

#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// Omega^2 R_o (m/s^2): the carrier's field.
double carrier_field(const DrumOrbit& orbit);
/// The drum's speed ratio k = omega / Omega - 1 (omega its absolute rate).
double speed_ratio(const DrumConfig& drum);
/// |1 + k| at which the wall holds a ball whose centre runs at rho (m) from the drum's centre.
double critical_speed_ratio(const DrumOrbit& orbit, double rho);

enum class PlanetaryRegime { released, partly_held, held };

/// Whether the wall holds every particle (|1 + k| above the critical ratio of the largest, whose
/// centre path is the smallest), only the smaller ones, or releases them all.
PlanetaryRegime predicted_regime(const DrumConfig& drum, double r_min, double r_max);
std::string regime_text(PlanetaryRegime regime);

}  // namespace drumlab
