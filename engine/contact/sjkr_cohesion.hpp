#pragma once
// Dry adhesion: the simplified JKR model of LIGGGHTS (cohesion_model_sjkr.h, `cohesion sjkr`),
// a law part that acts only while the spheres overlap:
//     F = k_c A,   A = pi a^2,
// attractive along the line of centres, k_c the cohesion energy density (J/m^3 = Pa) and a the
// radius of the lens where the two spheres intersect, from the overlap geometry as LIGGGHTS
// computes it: at centre distance d,
//     a^2 = -(d - r_i - r_j)(d + r_i - r_j)(d - r_i + r_j)(d + r_i + r_j) / (4 d^2).
// (For a small overlap delta = r_i + r_j - d, a^2 ~ 2 R* delta with R* = r_i r_j / (r_i + r_j).)
//
// Pull-off, as a consequence (Hertz normal law, a^2 ~ 2 R* delta): the adhesion grows like delta
// and the Hertz repulsion 4/3 E* sqrt(R*) delta^(3/2) faster, so a pair at rest settles at
//     delta_eq = (3 pi k_c)^2 R* / (4 E*^2)          (adhesion = repulsion, stable),
// and pulling it apart needs at most the largest net attraction, at delta_m = (4/9) delta_eq,
//     F_pull = (2/3) pi^3 k_c^3 R*^2 / E*^2.
// At delta = 0 the lens and the force vanish: sjkr has no tensile force beyond contact, so the
// pull-off distance is 0 (no range, the search margin is unchanged).
//
// State per contact: [0] 1 while the contact is adhesive (overlapping), else 0; [1] its age, the
// time (s) since it formed (what a Bond reports).
#include <cstddef>
#include <numbers>

namespace drumlab {

struct SjkrCohesion {
  static constexpr std::size_t kStateSize = 2;

  double energy_density = 0.0;  ///< k_c, J/m^3

  /// pi a^2 of two spheres whose centres are `dist` apart (m^2); 0 unless they overlap.
  static double lens_area(double dist, double r_i, double r_j) {
    if (!(dist < r_i + r_j)) return 0.0;
    const double a2 = -(dist - r_i - r_j) * (dist + r_i - r_j) * (dist - r_i + r_j) *
                      (dist + r_i + r_j) / (4.0 * dist * dist);
    return std::numbers::pi * a2;
  }
  /// pi a^2 of a sphere of radius r cut by a plane at overlap delta (m^2): a^2 = 2 r delta -
  /// delta^2.
  static double wall_lens_area(double delta, double r) {
    return delta > 0.0 ? std::numbers::pi * delta * (2.0 * r - delta) : 0.0;
  }
  /// The adhesive force (N, attractive, >= 0) on a lens of area `area`.
  double force(double area) const { return energy_density * area; }
  /// The pull-off force of the header (N) for a Hertz contact of E* (Pa), R* (m).
  double pull_off_force(double e_star, double r_star) const {
    const double pi = std::numbers::pi;
    const double k = energy_density;
    return (2.0 / 3.0) * pi * pi * pi * k * k * k * r_star * r_star / (e_star * e_star);
  }
  /// The overlap of a pair at rest (m): delta_eq of the header.
  double rest_overlap(double e_star, double r_star) const {
    const double x = 3.0 * std::numbers::pi * energy_density / e_star;
    return x * x * r_star / 4.0;
  }

  static bool bond(const double* state) { return state[0] > 0.0; }
  static double bond_age(const double* state) { return state[1]; }
};

}  // namespace drumlab
