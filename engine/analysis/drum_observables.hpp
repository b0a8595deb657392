#pragma once
// Observables of the granular bed in a rotating drum, measured from one particle state (positions,
// velocities, radii, masses) in the drum frame: axis along z through x = y = 0, gravity as given.
//
// The cross-section is described by two unit vectors perpendicular to the axis:
//   up    = -(gravity projected onto the cross-section), normalised;
//   carry = direction of the drum wall's velocity at the lowest point of the mantle, relative to
//           the field: sign(omega - field_omega) z_hat x (-up); +z_hat x (-up) when equal.
// `field_omega` is the rate at which the body force turns about the axis: 0 for gravity, the
// carrier's Omega for a planetary drum whose carrier field outweighs gravity across the axis
// (there the wall drives the bed at omega - Omega relative to the field; measure_drum(sim) sets
// it). With gravity -y and omega > 0 (counter-clockwise), up = +y and carry = +x: the drum lifts
// the bed on the +x side.
//
// Definitions (all documented in the fields below):
// * Free surface: the cross-section is cut into columns (width `column_width` along carry and
//   along z); the height of a column is the highest particle top (up . x + r) in it; the surface
//   height at a carry position is the median over the z columns (robust against single particles
//   in flight). A straight line is fitted (least squares) to the surface heights of the central
//   part of the surface (`end_exclusion` of the occupied extent left out at each end, where the
//   wall bends the surface).
// * Dynamic angle of repose: atan of the fitted slope, degrees, positive when the surface rises
//   in the carry direction (the usual case in a turning drum).
// * Flowing layer: particles in the same central window are binned by their depth below the
//   fitted line (along its normal); the mean velocity component along the downhill tangent of
//   the line is computed per bin. The layer thickness is the depth of the first sign change of
//   that mean velocity from downhill (> 0, flowing) to uphill (<= 0, carried up with the drum),
//   interpolated linearly between bins. 0 when the top bin does not move downhill (no flowing
//   layer: a bed at rest or turning as a solid body); the whole bed depth when no bin moves uphill.
// * Particles in free flight: particles with no other particle and no drum mantle within
//   `flight_gap` of their surface.
// * Relative speed: mean over all particles of |v - omega z_hat x x|, the speed relative to a
//   rigid rotation with the drum. ~0 for a bed turning as a solid body (or at rest); in a steady
//   flow the material lifted by the drum must stream back through the flowing layer, so its
//   time mean is of order omega R whatever the regime (see flow_regime.hpp).
#include <cstddef>
#include <optional>
#include <vector>

#include "engine/particles.hpp"
#include "engine/types.hpp"

namespace drumlab {

class Simulation;

/// What the observables need to know about the drum.
struct DrumGeometry {
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  ///< drum frame, m/s^2
  double omega = 0.0;                    ///< rad/s about +z
  double field_omega = 0.0;              ///< rad/s: the body force turns at this rate (see top)
  double radius = 0.0;                   ///< mantle radius R, m
  std::optional<double> period_z;        ///< depth of a drum with periodic ends
};

struct ObservableOptions {
  double column_width = 0.0;   ///< m; 0: the diameter of the largest particle
  double end_exclusion = 0.2;  ///< share of the surface's extent left out at each end, [0, 0.45]
  double flight_gap = 0.0;     ///< m; 0: a quarter of the smallest radius
};

/// One point of the free surface: the surface height (along up) at a carry position, both m.
struct SurfaceHeight {
  double h = 0.0;  ///< position along carry, m (the centre of a column bin)
  double u = 0.0;  ///< surface height along up, m
};

/// A straight line u = a + b h (and a cubic) fitted to the central part of a surface profile.
struct SurfaceFit {
  double a = 0.0;
  double b = 0.0;
  double h_lo = 0.0;  ///< the central window along carry, m
  double h_hi = 0.0;
  double angle_deg = 0.0;  ///< atan(b), degrees
  std::size_t points = 0;
  double chord = 0.0;      ///< extent of the fitted points along carry, m
  double rms = 0.0;        ///< rms residual of the line fit, m
  double curvature = 0.0;  ///< max |cubic - line| / chord (0 with fewer than 5 points)
};

/// Fits the line (and the cubic) to `profile` (sorted by h) without its `end_exclusion` share of
/// the extent at each end; nullopt with fewer than 3 points left.
std::optional<SurfaceFit> fit_surface_profile(const std::vector<SurfaceHeight>& profile,
                                              double end_exclusion);

struct DrumObservables {
  std::size_t particles = 0;
  bool surface_found = false;        ///< at least 3 surface points in the central window
  double angle_of_repose_deg = 0.0;  ///< degrees, positive rising along `carry`
  std::size_t surface_points = 0;    ///< columns used for the line fit
  double surface_chord = 0.0;        ///< extent (along carry) of the fitted points, m
  double surface_rms = 0.0;          ///< rms residual of the line fit, m
  /// Largest distance between a cubic fitted to the same surface points and the line, divided by
  /// the chord: ~0 for a flat surface, a few per cent for the S shape of a cascading bed.
  double surface_curvature = 0.0;
  double flowing_layer_thickness = 0.0;  ///< m, see the header comment
  double bed_depth = 0.0;  ///< deepest particle centre below the line in the central window, m
  double mean_kinetic_energy = 0.0;     ///< translational, J per particle
  double mean_rotational_energy = 0.0;  ///< J per particle
  double solid_body_energy = 0.0;       ///< mean 1/2 m (omega rho)^2 of a bed turning rigidly, J
  Vec3 centre_of_mass = Vec3::Zero();   ///< mass-weighted, m
  double com_offset = 0.0;  ///< distance of the COM from the axis in the cross-section / R
  /// Angle of repose from the centre of mass (MercuryDPM's RotatingDrumWet: the angle of the COM
  /// about the axis from straight down, atan2(com . carry, -com . up), degrees). For a bed whose
  /// cross-section is a circular segment under a flat surface it equals the surface's angle (the
  /// COM lies on the chord's perpendicular through the axis); it needs no surface fit.
  double com_angle_deg = 0.0;
  double airborne_fraction = 0.0;  ///< share of particles in free flight
  double upper_fraction = 0.0;     ///< share of particle centres above the axis (along up)
  double relative_speed = 0.0;     ///< mean |v - omega z_hat x x| over the particles, m/s
  double wall_speed = 0.0;  ///< |omega - field_omega| R: the wall's speed against the field, m/s
  double field = 0.0;       ///< the body force's part across the axis, m/s^2
  double radius = 0.0;      ///< the drum's mantle radius R, m
  /// The surface heights of all column bins (before the end exclusion), sorted by h; the bins
  /// sit at fixed positions, so profiles of several samples can be averaged bin by bin.
  std::vector<SurfaceHeight> surface_profile;
  Vec3 up = Vec3::Zero();  ///< the cross-section axes used (unit vectors)
  Vec3 carry = Vec3::Zero();
};

/// Measures the observables. Throws InputError if the particle arrays disagree in size, the
/// radius is not positive, gravity has no component across the axis or an option is out of range.
DrumObservables measure_drum(const Particles& particles, const DrumGeometry& drum,
                             const ObservableOptions& options = {});
/// Same, for the current state of a simulation (its gravity, drum omega, radius and ends).
DrumObservables measure_drum(const Simulation& sim, const ObservableOptions& options = {});

}  // namespace drumlab
