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
// time (s) since it formed (what a Bond reports). No per-particle state: the wall needs none.
// The cohesive-part interface (cohesive_part.hpp): range 0; no events (no liquid moves); bond =
// an adhesive contact (k_c > 0).
#include <cstddef>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

#include "engine/contact/cohesive_part.hpp"

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

  // --- the cohesive-part interface (cohesive_part.hpp) ---
  static constexpr bool kHasEvents = false;
  static constexpr bool kHoldsLiquid = false;

  /// The scene's [cohesion] (nullopt without), its values checked by the scene validation
  /// (engine/scene/scene_validation.hpp, law_problem), which the contact model runs first.
  static std::optional<SjkrCohesion> from_scene(const SceneConfig& scene) {
    if (!scene.cohesion.enabled) return std::nullopt;
    return SjkrCohesion{scene.cohesion.energy_density};
  }
  double range() const { return 0.0; }  // no tensile force beyond contact (header)
  double wall_range() const { return 0.0; }
  std::vector<std::string_view> particle_arrays(std::size_t) const { return {}; }
  bool moves_films() const { return false; }

  static bool live(const double* s) { return s[0] > 0.0; }
  bool event(const double*, double) const { return false; }
  /// Adhesive while overlapping (the flag set, the age counted from the step it formed), else
  /// the flag and age cleared.
  void advance_pair(const PairGap& g, double* s, double*, double dt, double& pull) const {
    if (g.gap < 0.0) {
      pull += force(lens_area(g.dist, g.p.radius[g.i], g.p.radius[g.j]));
      s[1] = s[0] > 0.0 ? s[1] + dt : 0.0;
      s[0] = 1.0;
    } else {
      s[0] = 0.0;
      s[1] = 0.0;
    }
  }
  void drop(double*, double*, Index, Index) const {}

  struct WallState {};
  bool acts_at_wall() const { return true; }
  WallState wall_state(Particles&, std::size_t) const { return {}; }
  bool wall_live(const WallState&, Index, std::size_t) const { return false; }
  void advance_wall(WallState&, const WallSite& site, double*, double, double& pull) const {
    if (site.g.gap < 0.0) pull += force(wall_lens_area(-site.g.gap, site.p.radius[site.i]));
  }

  bool bonds() const { return energy_density > 0.0; }
  static bool bonded(const double* s) { return s[0] > 0.0; }
  BondShare bond_share(const PairGap& g, const double* s) const {
    return {0.0, force(lens_area(g.dist, g.p.radius[g.i], g.p.radius[g.j])), s[1]};
  }
  static double liquid(const double*) { return 0.0; }
};

}  // namespace drumlab
