#include "engine/scene/scene_features.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/drum_orbit.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab {
namespace {

/// The grid a search method name uses (a Verlet list: its builder's): "2D", "3D", "none" (brute)
/// or "auto".
std::string grid_of(const std::string& method) {
  if (method == "auto") return "auto";
  const auto parsed = parse_search_method(method);
  if (!parsed) return "3D";  // the loader refuses unknown names
  return std::string(search_grid_name(parsed->method->grid));
}

SceneFeature term(std::string name, bool needed, std::string why) {
  return {std::move(name), needed ? FeatureUse::needed : FeatureUse::skipped, std::move(why)};
}

SceneFeature tangential(const char* who, const char* key, double mu) {
  return term(fmt::format("tangential history ({})", who), mu > 0.0,
              mu > 0.0 ? fmt::format("{} = {} > 0: Mindlin spring with history", key, mu)
                       : fmt::format("{} = 0: no tangential force, no history update", key));
}

SceneFeature rolling(const char* who, const char* key, double mu_r, bool spring) {
  return term(fmt::format("rolling resistance ({})", who), mu_r > 0.0,
              mu_r > 0.0 ? fmt::format("{} = {} > 0{}", key, mu_r,
                                       spring ? ": contact.rolling = spring (xi_r per contact, "
                                                "largest torque mu_r |F_n| 2 R*)"
                                              : "")
                         : fmt::format("{} = 0: no rolling torque", key));
}

SceneFeature grid_feature(const SceneConfig& scene, const SceneFeatures& f) {
  const std::string grid = grid_of(scene.search_method);
  const std::string depth =
      fmt::format("depth {} m = {:.3g} largest diameters", scene.drum.depth, f.depth_in_diameters);
  if (!f.shallow) {
    return {"3D search grid", FeatureUse::needed,
            fmt::format("{} > {:g}: deep drum, a 3D grid pays (search = {})", depth,
                        kShallowDepthInDiameters, scene.search_method)};
  }
  if (grid == "2D") {
    return {"3D search grid", FeatureUse::skipped,
            fmt::format("{} <= {:g}: shallow, the scene's {} uses a 2D grid (cells span the depth)",
                        depth, kShallowDepthInDiameters, scene.search_method)};
  }
  return {"3D search grid", FeatureUse::available,
          fmt::format("{} <= {:g}: shallow, a 2D grid (m2) suffices, but search = {} ({}); use "
                      "--method m2 or verlet:m2",
                      depth, kShallowDepthInDiameters, scene.search_method,
                      grid == "auto" ? "decided at run time" : grid)};
}

// The cohesive law parts: what [liquid] and [cohesion] switch on (engine/contact/cohesion_loops).
void add_cohesion_terms(const SceneConfig& scene, SceneFeatures& f) {
  const LiquidConfig& l = scene.liquid;
  const CohesionConfig& c = scene.cohesion;
  f.cohesion = l.enabled || c.enabled;
  if (!f.cohesion) {
    f.list.push_back({"cohesion", FeatureUse::skipped,
                      "no [liquid] and no [cohesion] table: dry contacts only, no cohesive pass, "
                      "search margin 0"});
    return;
  }
  f.list.push_back(
      term("cohesion", true,
           fmt::format("{}{}{}: one serial pass over the listed pairs after the "
                       "contact forces",
                       l.enabled ? "[liquid]" : "", l.enabled && c.enabled ? " + " : "",
                       c.enabled ? "[cohesion]" : "")));
  f.list.push_back(
      term("liquid bridges", l.enabled,
           l.enabled ? "Willett bridges formed on contact, kept up to s_rup (the search margin)"
                     : "no [liquid]: no bridges, search margin 0"));
  std::string own;  // classes with their own liquid_content
  for (const ParticleClass& c : scene.classes) {
    if (c.liquid_content) own += fmt::format(", class {} {}", c.name, *c.liquid_content);
  }
  f.list.push_back(term(
      "liquid migration", l.migration,
      l.migration ? fmt::format("liquid_content = {}{}: films give and take the bridges' liquid{}",
                                l.liquid_content, own,
                                l.rupture_to_bridges > 0.0
                                    ? fmt::format(", rupture_to_bridges = {} (a ruptured "
                                                  "bridge feeds the particles' other bridges)",
                                                  l.rupture_to_bridges)
                                    : std::string())
      : l.enabled
          ? fmt::format("bridge_volume = {} m^3: every bridge the same, no films", l.bridge_volume)
          : std::string("no [liquid]")));
  f.list.push_back(term("wall bridges", l.enabled && l.wall_bridges,
                        !l.enabled       ? "no [liquid]"
                        : l.wall_bridges ? "particle-wall bridges (R = 2 Rp) on mantle and caps"
                                         : "liquid.wall_bridges = false"));
  f.list.push_back(term(
      "viscous bridge force", l.viscosity > 0.0,
      l.viscosity > 0.0 ? fmt::format("viscosity = {} Pa s, min_gap = {} m", l.viscosity, l.min_gap)
                        : "viscosity = 0: capillary force only"));
  f.list.push_back(term(
      "binder spray", !scene.sprays.empty(),
      scene.sprays.empty()
          ? std::string("no [[spray]]: no droplets, no droplet pass")
          : fmt::format("{} nozzle(s): droplets fly outside the contact search, a particle grid "
                        "near them only while some fly",
                        scene.sprays.size())));
  const bool wets = std::any_of(scene.sprays.begin(), scene.sprays.end(),
                                [](const SprayConfig& c) { return c.at_wall == SprayAtWall::wet; });
  f.list.push_back(term("wall film", wets,
                        wets
                            ? std::string("a nozzle has at_wall = \"wet\": droplets that reach the "
                                          "wall wet it; a pass over the wall's particles while "
                                          "it holds liquid")
                            : std::string("no nozzle wets the wall (at_wall = \"lost\")")));
  f.list.push_back(term("dry adhesion (sjkr)", c.enabled,
                        c.enabled ? fmt::format("cohesion.energy_density = {} J/m^3 (k_c pi a^2 "
                                                "while overlapping)",
                                                c.energy_density)
                                  : "no [cohesion]"));
}

}  // namespace

double bond_number(const SceneConfig& scene, std::size_t cls) {
  const double g = scene.gravity.norm();
  const double r = scene.classes.at(cls).mean_radius();  // a distribution: its mean
  const double m = scene.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  if (!(g > 0.0) || !(m > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  double f0 = 0.0;
  if (scene.liquid.enabled) {
    // Willett's R = 2 r r / (r + r) = r for two spheres of the class.
    f0 += 2.0 * std::numbers::pi * r * scene.liquid.surface_tension *
          std::cos(scene.liquid.contact_angle_deg * std::numbers::pi / 180.0);
  }
  return f0 / (m * g);
}

SceneFeatures scene_features(const SceneConfig& scene) {
  SceneFeatures f;
  f.pair_tangential = scene.material.friction > 0.0;
  f.wall_tangential = scene.wall.friction > 0.0;
  f.pair_rolling = scene.material.rolling_friction > 0.0;
  f.wall_rolling = scene.wall.rolling_friction > 0.0;
  f.rotation = f.pair_tangential || f.wall_tangential || f.pair_rolling || f.wall_rolling;
  f.cohesion = false;
  f.end_caps = scene.drum.ends == DrumEnds::caps;
  const double largest = 2.0 * scene.max_radius();
  f.depth_in_diameters = largest > 0.0 ? scene.drum.depth / largest : 0.0;
  f.shallow = largest > 0.0 && f.depth_in_diameters <= kShallowDepthInDiameters;
  f.grid_2d = grid_of(scene.search_method) == "2D";

  const bool spring = scene.contact.rolling == RollingLaw::spring;
  f.list.push_back(tangential("particle-particle", "material.friction", scene.material.friction));
  f.list.push_back(tangential("particle-wall", "wall.friction", scene.wall.friction));
  f.list.push_back(term("rotation (angular velocity)", f.rotation,
                        f.rotation ? "some contact applies a torque (friction or rolling > 0)"
                                   : "no friction and no rolling resistance: no torque, "
                                     "angular velocities are not integrated"));
  f.list.push_back(rolling("particle-particle", "material.rolling_friction",
                           scene.material.rolling_friction, spring));
  f.list.push_back(
      rolling("particle-wall", "wall.rolling_friction", scene.wall.rolling_friction, spring));
  add_cohesion_terms(scene, f);
  f.list.push_back(term("end-cap contacts", f.end_caps,
                        f.end_caps ? "drum.ends = caps: mantle and both caps tested per particle"
                                   : "drum.ends = periodic: only the mantle is tested"));
  f.list.push_back(term(
      "triangle walls", scene.has_meshes(),
      scene.has_meshes()
          ? fmt::format("{} [[wall.mesh]], {} [[wall.lifters]]: every particle looked up in each "
                        "mesh's grid (drum frame), one contact per smooth patch with history",
                        scene.meshes.size(), scene.lifters.size())
          : std::string("no [[wall.mesh]] or [[wall.lifters]]: no mesh grid, no mesh pass")));
  const DrumOrbit& orbit = scene.drum.orbit;
  f.list.push_back(term("planetary carrier field", orbit.active(),
                        orbit.active()
                            ? fmt::format("[drum.orbit]: Omega^2 R_o = {:.4g} m/s^2 added to "
                                          "gravity, turning with the arm (two cosines a step)",
                                          carrier_field(orbit))
                            : std::string("no [drum.orbit]: constant gravity")));
  f.list.push_back(grid_feature(scene, f));
  f.list.push_back({"output writers / VTK objects", FeatureUse::command_line,
                    "not in the scene: created only for --vtu/--h5/--checkpoint or render; "
                    "without them no writer and no VTK object exists"});
  return f;
}

const char* feature_use_name(FeatureUse use) {
  switch (use) {
    case FeatureUse::needed:
      return "needed";
    case FeatureUse::skipped:
      return "skipped";
    case FeatureUse::available:
      return "available";
    case FeatureUse::not_implemented:
      return "not implemented";
    case FeatureUse::command_line:
      return "command line";
  }
  return "?";
}

}  // namespace drumlab
