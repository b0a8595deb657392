#pragma once
// What the engine needs to compute for a scene, and what it leaves out, decided from the
// SceneConfig alone (`drumlab info` prints it; `drumlab bench skips` measures each skip).
// The contact terms mirror the choices ContactModel makes (engine/contact/contact_model.cpp):
//   tangential history   pair: material.friction > 0; wall: wall.friction > 0
//   rolling resistance   pair: material.rolling_friction > 0; wall: wall.rolling_friction > 0
//   rotation             integrated only if one of the four terms above can apply a torque
//   end-cap contacts     only with drum.ends = caps (periodic ends test the mantle only)
//   cohesion             [liquid] (bridges, migration, wall bridges, viscous term) and/or
//                        [cohesion] (sjkr): one serial pass after the contact forces
// A 2D search grid (cells spanning
// the depth) suffices for a shallow drum; whether the run uses one depends on its search method.
// Output writers and VTK objects are not known from the scene: the command line creates them.
#include <string>
#include <vector>

#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// A drum is shallow (a 2D grid suffices) when its depth is at most this many largest particle
/// diameters. The paper's shallow drum is 5 largest diameters deep, its deep one 67.
inline constexpr double kShallowDepthInDiameters = 10.0;

enum class FeatureUse {
  needed,           ///< the engine computes it for this scene
  skipped,          ///< the engine leaves it out for this scene
  available,        ///< a skip the scene could take but does not (e.g. a 3D grid when 2D suffices)
  not_implemented,  ///< the engine has no such term
  command_line,     ///< not decided by the scene (output writers)
};

/// One line of the "needs / skips" list.
struct SceneFeature {
  std::string term;  ///< e.g. "tangential history (particle-particle)"
  FeatureUse use = FeatureUse::needed;
  std::string why;  ///< one line, with the scene values it follows from
};

struct SceneFeatures {
  bool pair_tangential = false;
  bool wall_tangential = false;
  bool pair_rolling = false;
  bool wall_rolling = false;
  bool rotation = false;  ///< angular velocities integrated (some contact applies a torque)
  bool cohesion = false;  ///< [liquid] or [cohesion]: a cohesive pass
  bool end_caps = false;  ///< end-cap wall contacts (drum.ends = caps)
  bool shallow = false;   ///< depth <= kShallowDepthInDiameters largest diameters
  bool grid_2d = false;   ///< the scene's search method uses a 2D grid (m1, m2, m4, verlet:m2...)
  double depth_in_diameters = 0.0;  ///< drum depth / largest particle diameter
  std::vector<SceneFeature> list;   ///< every term above, in print order
};

/// Decides the features of `scene` (no simulation, no fill).
SceneFeatures scene_features(const SceneConfig& scene);

/// Bond number of class `cls`: the bridge's touching force F0 = 2 pi r gamma cos(theta) between
/// two spheres of the class (Willett's R = r) over the sphere's weight m g; 0 for a scene without
/// [liquid], NaN without gravity.
double bond_number(const SceneConfig& scene, std::size_t cls);

/// "needed", "skipped", "available", "not implemented", "command line".
const char* feature_use_name(FeatureUse use);

}  // namespace drumlab
