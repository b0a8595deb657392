#include "engine/io/restart_check.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "engine/contact/bond.hpp"
#include "engine/contact/liquid_bridge.hpp"

namespace drumlab {
namespace {

using Problem = std::optional<SceneProblem>;

Problem at_row(std::string_view dataset, std::size_t row, std::string reason) {
  return SceneProblem{fmt::format("particles/{}: row {}", dataset, row), std::move(reason)};
}

bool close(double value, double expected) {
  return std::abs(value - expected) <= 1e-12 * std::abs(expected);
}

/// The radius, mass, inverse mass and inverse inertia of row i against its class.
Problem check_body(const SceneConfig& scene, const Particles& p, std::size_t i) {
  const std::size_t c = p.size_class[i];
  if (c >= scene.classes.size()) {
    return at_row("size_class", i,
                  fmt::format("class {}, the scene has {} [[particles]] classes (a checkpoint of "
                              "another scene?)",
                              c, scene.classes.size()));
  }
  const ParticleClass& k = scene.classes[c];
  const double r = p.radius[i];
  if (!k.polydisperse() && !close(r, k.radius)) {
    return at_row("radius", i,
                  fmt::format("{} m, the scene's class '{}' has {} m (a checkpoint of another "
                              "scene?)",
                              r, k.name, k.radius));
  }
  if (k.polydisperse() && !k.size().holds(r, 1e-12)) {
    return at_row("radius", i,
                  fmt::format("{} m, outside the radii of the scene's class '{}' ({}; a checkpoint "
                              "of another scene?)",
                              r, k.name, k.size().describe()));
  }
  const double m = scene.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  if (!close(p.mass[i], m)) {
    return at_row("mass", i,
                  fmt::format("{} kg, radius {} m and material.density {} kg/m^3 give {} kg",
                              p.mass[i], r, scene.material.density, m));
  }
  if (!close(p.inv_mass[i], 1.0 / p.mass[i])) {
    return at_row("inv_mass", i,
                  fmt::format("{} 1/kg, not 1 / mass = {}", p.inv_mass[i], 1.0 / p.mass[i]));
  }
  const double inv_inertia = 1.0 / (0.4 * p.mass[i] * r * r);
  if (!close(p.inv_inertia[i], inv_inertia)) {
    return at_row("inv_inertia", i,
                  fmt::format("{}, a solid sphere of this mass and radius has {}", p.inv_inertia[i],
                              inv_inertia));
  }
  return std::nullopt;
}

Problem check_motion(const Particles& p, std::size_t i) {
  const std::pair<std::string_view, const std::vector<Vec3>*> vectors[] = {
      {"position", &p.position},
      {"velocity", &p.velocity},
      {"omega", &p.omega},
      {"force", &p.force},
      {"torque", &p.torque}};
  for (const auto& [name, values] : vectors) {
    if (!(*values)[i].allFinite()) return at_row(name, i, "not a finite vector");
  }
  return std::nullopt;
}

Problem check_ids(const Particles& p) {
  std::vector<std::pair<std::uint32_t, std::size_t>> ids(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) ids[i] = {p.id[i], i};
  std::sort(ids.begin(), ids.end());
  for (std::size_t k = 1; k < ids.size(); ++k) {
    if (ids[k].first == ids[k - 1].first) {
      return at_row("id", ids[k].second,
                    fmt::format("id {} is also the id of row {}", ids[k].first, ids[k - 1].second));
    }
  }
  return std::nullopt;
}

/// True for the law parts' arrays that hold a liquid volume (m^3) or a bridge's age (s).
bool holds_amount(std::string_view name) {
  const auto in = [&](const auto& names) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  return name == kLiquidFilmArray || in(kWallBridgeVolumeArrays) || in(kWallBridgeAgeArrays);
}

/// The law parts' arrays (films, wall bridges, wall and mesh springs): finite; a volume or an age
/// not below zero beyond round-off (1e-9 of the array's largest value: a film drawn down to a
/// bridge's volume may end an ulp below zero). A NaN film would spread through the bridges it
/// forms into the liquid totals; a negative one would form a bridge of negative volume.
Problem check_extra(const Particles& p) {
  for (const ParticleArray& a : p.extra) {
    const std::string dataset = "extra_" + a.name;
    double largest = 0.0;
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      if (!std::isfinite(a.values[i])) return at_row(dataset, i, "not finite");
      largest = std::max(largest, std::abs(a.values[i]));
    }
    if (!holds_amount(a.name)) continue;
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      if (a.values[i] < -1e-9 * largest) {
        return at_row(dataset, i, fmt::format("{}, below zero (a volume or an age)", a.values[i]));
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<SceneProblem> restart_particles_problem(const SceneConfig& scene,
                                                      const Particles& p) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (auto problem = check_body(scene, p, i)) return problem;
    if (auto problem = check_motion(p, i)) return problem;
  }
  if (auto problem = check_extra(p)) return problem;
  return check_ids(p);
}

void check_restart_count(const SceneConfig& scene, std::size_t count, std::string_view where) {
  if (scene.fill.kind == FillKind::random && count != scene.fill.count) {
    throw InputError(fmt::format(
        "{}: particles: {} in the checkpoint, the scene's fill.count is {} (a checkpoint of "
        "another scene?)",
        where, count, scene.fill.count));
  }
}

void check_restart_particles(const SceneConfig& scene, const Particles& p, std::string_view where) {
  if (const auto problem = restart_particles_problem(scene, p)) {
    throw InputError(fmt::format("{}: {}: {}", where, problem->key, problem->reason));
  }
}

}  // namespace drumlab
