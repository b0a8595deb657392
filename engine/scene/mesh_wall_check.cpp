#include "engine/scene/mesh_wall_check.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/scene/material_check.hpp"

namespace drumlab {
namespace {

using Problem = std::optional<SceneProblem>;

Problem fail(const std::string& key, std::string reason) {
  return SceneProblem{key, std::move(reason)};
}

Problem check_material(const std::string& key, const MeshMaterial& m) {
  const Material full{1.0,           m.youngs_modulus, m.poisson_ratio,
                      m.restitution, m.friction,       m.rolling_friction};
  if (auto p = material_problem(full)) return fail(key + "." + p->key, std::move(p->reason));
  return std::nullopt;
}

Problem check_mesh(const SceneConfig& s, const MeshWallConfig& c, const std::string& key) {
  if (!(c.scale > 0.0 && std::isfinite(c.scale))) {
    return fail(key + ".scale", fmt::format("must be a finite number > 0, got {}", c.scale));
  }
  if (!(c.smooth_angle_deg >= 0.0 && c.smooth_angle_deg < 180.0)) {
    return fail(key + ".smooth_angle_deg",
                fmt::format("must be in [0, 180) degrees, got {}", c.smooth_angle_deg));
  }
  if (c.attach == MeshAttach::lab && s.drum.orbit.active()) {
    return fail(key + ".attach",
                "\"lab\" not with [drum.orbit] (the drum's frame moves round the central axis; "
                "attach the mesh to the drum)");
  }
  return check_material(key, c.material);
}

Problem check_lifters(const SceneConfig& s, const LifterWallConfig& c, const std::string& key) {
  const double radius = 0.5 * s.drum.diameter;
  if (!(c.height > 0.0 && c.height < radius)) {
    return fail(key + ".height", fmt::format("must be in (0, R = {} m), got {}", radius, c.height));
  }
  if (!(c.length >= 0.0 && c.length <= s.drum.depth)) {
    return fail(key + ".length", fmt::format("must be in [0, drum.depth = {} m] (0: the depth), "
                                             "got {}",
                                             s.drum.depth, c.length));
  }
  if (!(c.thickness >= 0.0 && c.thickness < c.height)) {
    return fail(key + ".thickness",
                fmt::format("must be in [0, height) (0: height / 8), got {}", c.thickness));
  }
  if (c.shape == LifterKind::angled) {
    if (!(c.angle_deg > 0.0 && c.angle_deg < 180.0)) {
      return fail(key + ".angle_deg",
                  fmt::format("must be in (0, 180) degrees, got {}", c.angle_deg));
    }
    if (!(c.tip >= 0.0 && c.tip < radius)) {
      return fail(key + ".tip", fmt::format("must be in [0, R) (0: height / 2), got {}", c.tip));
    }
  }
  if (!std::isfinite(c.phase_deg)) return fail(key + ".phase_deg", "must be a finite number");
  return check_material(key, c.material);
}

}  // namespace

std::optional<SceneProblem> mesh_wall_problem(const SceneConfig& s) {
  if (!s.has_meshes()) return std::nullopt;
  for (std::size_t i = 0; i < s.meshes.size(); ++i) {
    if (auto p = check_mesh(s, s.meshes[i], fmt::format("wall.mesh[{}]", i))) return p;
  }
  for (std::size_t i = 0; i < s.lifters.size(); ++i) {
    if (auto p = check_lifters(s, s.lifters[i], fmt::format("wall.lifters[{}]", i))) return p;
  }
  const std::string key = s.meshes.empty() ? "wall.lifters" : "wall.mesh";
  if (s.liquid.enabled && s.liquid.wall_bridges) {
    return fail(key,
                "not with wall bridges yet (liquid bridges do not form on triangle walls; set "
                "liquid.wall_bridges = false)");
  }
  if (!s.sprays.empty()) {
    return fail(key, "not with [[spray]] yet (droplets do not see the triangle walls)");
  }
  return std::nullopt;
}

}  // namespace drumlab
