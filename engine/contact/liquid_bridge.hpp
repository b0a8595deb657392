#pragma once
// Pendular liquid bridge between two spheres, or a sphere and the drum wall: a law part that acts
// beyond contact.
//
// Force: Willett, Adams, Johnson & Seville (2000), "Capillary bridges between two spheres",
// Langmuir 16, closed form for a bridge of volume V, with the conventions of MercuryDPM's
// LiquidMigrationWilletInteraction: effective radius R = 2 R1 R2 / (R1 + R2) (a wall: R = 2 Rp),
//     touching (s <= 0):  F = F0 = 2 pi R gamma cos(theta),
//     gap s > 0:          F = F0 / (1 + (1.05 + 2.5 s~) s~),   s~ = s sqrt(R / V),
// attractive, along the line of centres (the wall normal). Gap convention: s is the surface
// separation |x_i - x_j| - (r_i + r_j) (a wall: the particle's distance to the wall minus r),
// negative while they overlap. A bridge forms only on contact (s <= 0) and ruptures once
// s > s_rup = (1 + theta / 2) V^(1/3) (Lian, Thornton & Adams 1993, as in MercuryDPM): at
// s = s_rup it still pulls, beyond it the bridge is gone until they touch again.
//
// Optional viscous term (off with viscosity 0): the normal lubrication force of two spheres
// approaching in a liquid (Reynolds; Pitois, Moucheront & Chateau 2000),
//     F_v = 6 pi eta R*^2 v_n / max(s, s_min),   R* = R1 R2 / (R1 + R2) (a wall: R* = Rp),
// with v_n the normal relative velocity (> 0 separating), opposing it, while a bridge lives.
//
// Liquid migration (LiquidConfig::migration; MercuryDPM's LiquidMigrationWilletInteraction
// form()/rupture(), Mohan, Kloss, Khinast & Radl 2014 use the same bookkeeping): every particle
// carries a film volume (Particles array kLiquidFilmArray).
//   forming between particles: the bridge takes V = min(film_i + film_j, V_max), half from each
//     film; a film holding less than half gives all it has and the other gives the rest. Both
//     films empty: no bridge (the pair touches dry and tries again at the next step it touches).
//     With `proportional_draw` ([liquid] bridge_draw = "proportional", MercuryDPM's form()): a
//     bridge of V_max takes V_max film_i / (film_i + film_j) from i and the rest from j.
//   forming with the wall: V = min(film_i, V_max), all from the particle's film.
//   rupture between particles: half of V to each film (the equal split); with the wall: all of V
//     back to the particle's film. With `rupture_to_bridges` = c > 0 ([liquid]
//     rupture_to_bridges, MercuryDPM's distribution coefficient, LiquidMigrationWilletInteraction
//     ::rupture()): each particle's half goes, for the share c, to that particle's other live
//     particle-particle bridges, c V/2 / n to each of its n, each topped at V_max with the excess
//     to its film (add_shared), and the rest to its film; without another bridge the whole half
//     goes to its film. The ordered pass does that (cohesion_loops.cpp, RuptureSharing): it needs
//     the particle's other contacts.
// Without migration every bridge has the fixed volume LiquidConfig::bridge_volume and no film.
// State per contact: [0] V (m^3, 0: no bridge), [1] its age (s since it formed). State per
// particle (wall bridges): the volume and age of its bridge with each wall part, in the arrays
// kWallBridgeVolumeArrays / kWallBridgeAgeArrays; its film in kLiquidFilmArray (migration).
// The cohesive-part interface (cohesive_part.hpp): range = s_rup(V_max); events = a bridge forms
// or ruptures (films change); bond = a live bridge; liquid = V.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "engine/contact/bond.hpp"
#include "engine/contact/cohesive_part.hpp"

namespace drumlab {

/// Names of the per-particle arrays (Particles::extra) that keep each particle's bridge with
/// each wall part (mantle, low cap, high cap): its volume (m^3) and its age (s). Registered by
/// a scene with wall bridges; re-ordering and checkpoints carry them like every array.
inline constexpr std::array<std::string_view, 3> kWallBridgeVolumeArrays = {
    "wall_bridge_volume_mantle", "wall_bridge_volume_low_cap", "wall_bridge_volume_high_cap"};
inline constexpr std::array<std::string_view, 3> kWallBridgeAgeArrays = {
    "wall_bridge_age_mantle", "wall_bridge_age_low_cap", "wall_bridge_age_high_cap"};

/// Surface tension and contact angle of one kind of bridge (particle-particle or -wall).
struct BridgeLiquid {
  double surface_tension = 0.0;  ///< gamma, N/m
  double contact_angle = 0.0;    ///< theta, rad
  double f0_per_radius = 0.0;    ///< 2 pi gamma cos(theta), N/m

  BridgeLiquid() = default;
  BridgeLiquid(double gamma, double theta)
      : surface_tension(gamma),
        contact_angle(theta),
        f0_per_radius(2.0 * std::numbers::pi * gamma * std::cos(theta)) {}

  /// F0 = 2 pi R gamma cos(theta), N.
  double touching_force(double r_eff) const { return f0_per_radius * r_eff; }
  /// s_rup = (1 + theta / 2) V^(1/3), m.
  double rupture_distance(double v) const { return (1.0 + 0.5 * contact_angle) * std::cbrt(v); }
  /// gap > rupture_distance(v), decided exactly as that comparison, but with a cube root only
  /// when the gap lies within 1e-6 (relative) of s_rup: (gap / (1 + theta / 2))^3 against v
  /// settles every other case (its rounding is ~1e-15), and a bridge is checked every step.
  bool ruptured(double gap, double v) const {
    if (!(gap > 0.0)) return false;
    const double g = gap / (1.0 + 0.5 * contact_angle);
    const double g3 = g * g * g;
    if (g3 < (1.0 - 1e-6) * v) return false;
    if (g3 > (1.0 + 1e-6) * v) return true;
    return gap > rupture_distance(v);
  }
  /// Force of a bridge of volume v at gap s (N, attractive, >= 0), for s <= s_rup.
  double force(double gap, double r_eff, double v) const {
    const double f0 = touching_force(r_eff);
    if (gap <= 0.0) return f0;
    const double s = gap * std::sqrt(r_eff / v);
    return f0 / (1.0 + (1.05 + 2.5 * s) * s);
  }
};

struct LiquidBridge {
  static constexpr std::size_t kStateSize = 2;

  BridgeLiquid pair;  ///< particle-particle
  BridgeLiquid wall;  ///< particle-wall
  /// Fixed volume of every bridge (m^3) without migration; 0 with migration.
  double fixed_volume = 0.0;
  /// Largest bridge volume (m^3): the fixed volume, or the migration's maximum.
  double max_volume = 0.0;
  bool migration = false;
  bool proportional_draw = false;   ///< a bridge of V_max draws from the films in proportion
  double rupture_to_bridges = 0.0;  ///< c: the share of a ruptured half for the other bridges
  bool wall_bridges = false;
  double viscosity = 0.0;  ///< eta, Pa s; 0: no viscous term
  double min_gap = 0.0;    ///< s_min of the viscous term, m

  /// Willett's effective radius (m) of two spheres, and of a sphere against a wall.
  static double pair_radius(double r1, double r2) { return 2.0 * r1 * r2 / (r1 + r2); }
  static double wall_radius(double r) { return 2.0 * r; }

  /// The largest gap at which a particle-particle / particle-wall bridge can live (m).
  double range() const { return pair.rupture_distance(max_volume); }
  double wall_range() const { return wall_bridges ? wall.rupture_distance(max_volume) : 0.0; }

  /// Viscous normal force (N, along the normal towards i: positive repulsive) of a live bridge:
  /// -6 pi eta R*^2 v_n / max(s, s_min); r_star = R1 R2 / (R1 + R2) or Rp at a wall.
  double viscous_force(double gap, double r_star, double vn) const {
    return -6.0 * std::numbers::pi * viscosity * r_star * r_star * vn / std::max(gap, min_gap);
  }

  /// Volume of a new particle-particle bridge, drawn from the films fi, fj (migration) as the
  /// header says; 0: no bridge. Without migration: the fixed volume.
  double take_from_films(double& fi, double& fj) const {
    if (!migration) return fixed_volume;
    const double available = fi + fj;
    if (!(available > 0.0)) return 0.0;
    if (available <= max_volume) {
      fi = 0.0;
      fj = 0.0;
      return available;
    }
    if (proportional_draw) {
      const double share = fi / available;
      fi -= share * max_volume;
      fj -= (1.0 - share) * max_volume;
      return max_volume;
    }
    const double half = 0.5 * max_volume;
    if (fi <= half) {
      fj -= max_volume - fi;
      fi = 0.0;
    } else if (fj <= half) {
      fi -= max_volume - fj;
      fj = 0.0;
    } else {
      fi -= half;
      fj -= half;
    }
    return max_volume;
  }
  /// Volume of a new bridge with the wall, from the particle's film fi alone.
  double take_from_film(double& fi) const {
    if (!migration) return fixed_volume;
    const double v = std::min(fi, max_volume);
    fi -= v;
    return v;
  }

  // --- the cohesive-part interface (cohesive_part.hpp) ---
  static constexpr bool kHasEvents = true;
  static constexpr bool kHoldsLiquid = true;

  /// The scene's [liquid] (nullopt without), its values checked by the scene validation
  /// (engine/scene/scene_validation.hpp, law_problem), which the contact model runs first.
  static std::optional<LiquidBridge> from_scene(const SceneConfig& scene) {
    if (!scene.liquid.enabled) return std::nullopt;
    const LiquidConfig& l = scene.liquid;
    constexpr double kDegree = std::numbers::pi / 180.0;
    LiquidBridge b;
    b.pair = {l.surface_tension, l.contact_angle_deg * kDegree};
    b.wall = {l.wall_surface_tension, l.wall_contact_angle_deg * kDegree};
    b.migration = l.migration;
    b.proportional_draw = l.proportional_draw;
    b.rupture_to_bridges = l.migration ? l.rupture_to_bridges : 0.0;
    b.fixed_volume = l.migration ? 0.0 : l.bridge_volume;
    b.max_volume = l.migration ? l.max_bridge_volume : l.bridge_volume;
    b.wall_bridges = l.wall_bridges;
    b.viscosity = l.viscosity;
    b.min_gap = l.min_gap;
    return b;
  }

  /// The film with migration; the wall bridges' volume and age per wall part (`wall_parts`: 1
  /// with periodic ends, else 3) with wall bridges.
  std::vector<std::string_view> particle_arrays(std::size_t wall_parts) const {
    std::vector<std::string_view> names;
    if (migration) names.push_back(kLiquidFilmArray);
    if (!wall_bridges) return names;
    for (std::size_t w = 0; w < wall_parts; ++w) {
      names.push_back(kWallBridgeVolumeArrays[w]);
      names.push_back(kWallBridgeAgeArrays[w]);
    }
    return names;
  }
  bool moves_films() const { return migration; }

  static bool live(const double* s) { return s[0] > 0.0; }
  /// True if the pair's bridge forms or ruptures at this step (its films change): with a bridge
  /// beyond its rupture distance, or touching without one (MercuryDPM's form()/rupture()).
  bool event(const double* s, double gap) const {
    return s[0] > 0.0 ? pair.ruptured(gap, s[0]) : gap <= 0.0;
  }
  /// A bridge between i and j ends: its liquid goes back, half to each film (migration).
  static void rupture(double* s, double* film, Index i, Index j) {
    if (film != nullptr) {
      film[i] += 0.5 * s[0];
      film[j] += 0.5 * s[0];
    }
    s[0] = 0.0;
    s[1] = 0.0;
  }
  /// Ruptures, forms (films: nullptr without migration) or ages the bridge and adds its pull.
  void advance_pair(const PairGap& g, double* s, double* film, double dt, double& pull) const {
    if (s[0] > 0.0 && pair.ruptured(g.gap, s[0])) rupture(s, film, g.i, g.j);
    if (s[0] > 0.0) {
      s[1] += dt;
    } else if (g.gap <= 0.0) {
      double none = 0.0;
      const double v =
          film != nullptr ? take_from_films(film[g.i], film[g.j]) : take_from_films(none, none);
      s[0] = v;
      s[1] = 0.0;
    }
    if (!(s[0] > 0.0)) return;
    const double r_i = g.p.radius[g.i];
    const double r_j = g.p.radius[g.j];
    pull += pair.force(g.gap, pair_radius(r_i, r_j), s[0]);
    if (viscosity > 0.0) {
      const double vn = (g.p.velocity[g.i] - g.p.velocity[g.j]).dot(g.d) / g.dist;
      pull -= viscous_force(g.gap, r_i * r_j / (r_i + r_j), vn);
    }
  }
  /// Adds `v` (m^3) to a live bridge's state s, topped at V_max; returns the excess (m^3, >= 0).
  double add_shared(double* s, double v) const {
    const double sum = s[0] + v;
    const double excess = std::max(sum - max_volume, 0.0);
    s[0] = std::min(sum, max_volume);
    return excess;
  }
  /// A dropped pair is beyond every rupture distance: its bridge ends.
  void drop(double* s, double* film, Index i, Index j) const {
    if (s[0] > 0.0) rupture(s, film, i, j);
  }

  /// The wall bridges' arrays, per wall part.
  struct WallState {
    double* volume[kWallParts] = {};
    double* age[kWallParts] = {};
  };
  bool acts_at_wall() const { return wall_bridges; }
  WallState wall_state(Particles& p, std::size_t wall_parts) const {
    WallState w;
    for (std::size_t k = 0; k < wall_parts; ++k) {
      std::vector<double>* v = p.find_array(kWallBridgeVolumeArrays[k]);
      std::vector<double>* a = p.find_array(kWallBridgeAgeArrays[k]);
      if (v == nullptr || a == nullptr) throw std::logic_error("wall bridges without arrays");
      w.volume[k] = v->data();
      w.age[k] = a->data();
    }
    return w;
  }
  bool wall_live(const WallState& w, Index i, std::size_t part) const {
    return w.volume[part][i] > 0.0;
  }
  /// The bridge of particle i with one wall part: ruptures (all its liquid back to the film),
  /// forms (from the film alone), or ages; adds its pull.
  void advance_wall(WallState& w, const WallSite& site, double* film, double dt,
                    double& pull) const {
    const Index i = site.i;
    const WallGap& g = site.g;
    double& v = w.volume[site.part][i];
    double& age = w.age[site.part][i];
    if (v > 0.0 && wall.ruptured(g.gap, v)) {
      if (film != nullptr) film[i] += v;
      v = 0.0;
      age = 0.0;
    }
    if (v > 0.0) {
      age += dt;
    } else if (g.gap <= 0.0) {
      double none = 0.0;
      v = take_from_film(film != nullptr ? film[i] : none);
      age = 0.0;
    }
    if (!(v > 0.0)) return;
    const Particles& p = site.p;
    const double r = p.radius[i];
    pull += wall.force(g.gap, wall_radius(r), v);
    if (viscosity > 0.0) {
      const Vec3 point = p.position[i] - (r + std::max(g.gap, 0.0)) * g.normal;
      const double vn = (p.velocity[i] - Drum::wall_velocity(point, site.omega)).dot(g.normal);
      pull -= viscous_force(g.gap, r, vn);
    }
  }

  bool bonds() const { return true; }
  static bool bonded(const double* s) { return s[0] > 0.0; }
  BondShare bond_share(const PairGap& g, const double* s) const {
    const double r_i = g.p.radius[g.i];
    const double r_j = g.p.radius[g.j];
    return {s[0], pair.force(g.gap, pair_radius(r_i, r_j), s[0]), s[1]};
  }
  static double liquid(const double* s) { return s[0]; }
};

}  // namespace drumlab
