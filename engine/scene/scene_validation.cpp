#include "engine/scene/scene_validation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <fmt/format.h>

#include "engine/contact/liquid_bridge.hpp"
#include "engine/scene/material_check.hpp"
#include "engine/scene/mesh_wall_check.hpp"
#include "engine/search/contact_search.hpp"

namespace drumlab {
namespace {

using Problem = std::optional<SceneProblem>;

Problem fail(std::string key, std::string reason) {
  return SceneProblem{std::move(key), std::move(reason)};
}

/// "must be > 0<unit>, got v" unless v > 0.
Problem positive(std::string key, double v, std::string_view unit = "") {
  if (v > 0.0 && std::isfinite(v)) return std::nullopt;
  if (v > 0.0) return fail(std::move(key), fmt::format("must be a finite number, got {}", v));
  return fail(std::move(key), fmt::format("must be > 0{}, got {}", unit, v));
}

Problem non_negative(std::string key, double v) {
  if (v >= 0.0 && std::isfinite(v)) return std::nullopt;
  if (v >= 0.0) return fail(std::move(key), fmt::format("must be a finite number, got {}", v));
  return fail(std::move(key), fmt::format("must be >= 0, got {}", v));
}

Problem angle_deg(std::string key, double v) {
  if (v >= 0.0 && v < 90.0) return std::nullopt;
  return fail(std::move(key), fmt::format("must be in [0, 90) degrees, got {}", v));
}

Problem check_top_level(const SceneConfig& s) {
  if (s.name.empty()) return fail("name", "must not be empty");
  if (!s.gravity.allFinite()) return fail("gravity", "elements must be finite numbers");
  if (s.search_method.empty()) return fail("search", "must not be empty");
  if (s.search_method != "auto") {
    try {
      make_search(s.search_method);
    } catch (const InputError& e) {
      return fail("search", e.what());
    }
  }
  return std::nullopt;
}

/// A table's radii and shares: as many of each, every one > 0.
Problem check_size_table(const ParticleClass& c, const std::string& key) {
  if (c.radius != 0.0) return fail(key + ".radius", "not with distribution = \"table\"");
  if (c.radii.empty()) return fail(key + ".radii", "needs at least one radius");
  if (c.shares.size() != c.radii.size()) {
    return fail(key + ".shares",
                fmt::format("has {} values for {} radii", c.shares.size(), c.radii.size()));
  }
  for (std::size_t k = 0; k < c.radii.size(); ++k) {
    if (auto p = positive(fmt::format("{}.radii[{}]", key, k), c.radii[k])) return p;
    if (auto p = positive(fmt::format("{}.shares[{}]", key, k), c.shares[k])) return p;
  }
  return std::nullopt;
}

/// The radius or the size distribution of class `key` (engine/scene/size_distribution.hpp).
Problem check_size(const ParticleClass& c, const std::string& key) {
  if (c.distribution == SizeKind::table) return check_size_table(c, key);
  if (!c.radii.empty() || !c.shares.empty()) {
    return fail(key + ".radii", "only with distribution = \"table\"");
  }
  if (auto p = positive(key + ".radius", c.radius)) return p;
  if (c.distribution == SizeKind::single) {
    if (c.radius_sigma == 0.0) return std::nullopt;
    return fail(key + ".radius_sigma", "only with distribution = \"normal\" or \"lognormal\"");
  }
  if (auto p = positive(key + ".radius_sigma", c.radius_sigma, " m")) return p;
  if (auto p = positive(key + ".truncate", c.truncate, " standard deviations")) return p;
  const double low = c.radius - c.truncate * c.radius_sigma;
  if (c.distribution == SizeKind::normal && !(low > 0.0)) {
    return fail(key + ".radius_sigma",
                fmt::format("radius - truncate * radius_sigma = {} m: the normal's smallest radius "
                            "must be > 0 (lower radius_sigma or truncate)",
                            low));
  }
  return std::nullopt;
}

Problem check_classes(const SceneConfig& s) {
  if (s.classes.empty()) return fail("particles", "needs at least one [[particles]] class");
  if (s.classes.size() > 256) return fail("particles", "at most 256 size classes are supported");
  std::set<std::string_view> names;
  double sum = 0.0;
  for (std::size_t i = 0; i < s.classes.size(); ++i) {
    const ParticleClass& c = s.classes[i];
    const std::string key = fmt::format("particles[{}]", i);
    if (c.name.empty()) return fail(key + ".name", "must not be empty");
    if (!names.insert(c.name).second) {
      return fail(key + ".name", fmt::format("duplicate class '{}'", c.name));
    }
    if (auto p = check_size(c, key)) return p;
    if (!(c.volume_fraction > 0.0 && c.volume_fraction <= 1.0)) {
      return fail(key + ".volume_fraction",
                  fmt::format("must be in (0, 1], got {}", c.volume_fraction));
    }
    sum += c.volume_fraction;
  }
  if (std::abs(sum - 1.0) > 1e-6) {
    return fail("particles", fmt::format("volume_fraction values sum to {}, must sum to 1", sum));
  }
  return std::nullopt;
}

Problem check_orbit(const SceneConfig& s) {
  const DrumOrbit& o = s.drum.orbit;
  if (!o.active()) return std::nullopt;
  if (auto p = positive("drum.orbit.radius", o.radius, " m")) return p;
  if (!std::isfinite(o.omega) || o.omega == 0.0) {
    return fail("drum.orbit.omega",
                fmt::format("must be a finite, non-zero number (rad/s), got {}", o.omega));
  }
  if (!std::isfinite(o.phase)) return fail("drum.orbit.phase_deg", "must be a finite number");
  if (o.speed_ratio && !std::isfinite(*o.speed_ratio)) {
    return fail("drum.orbit.speed_ratio", "must be a finite number");
  }
  if (s.drum.tilt != 0.0) {
    return fail("drum.orbit",
                "only with an untilted drum (tilt_deg = 0; give gravity any direction instead)");
  }
  if (!s.sprays.empty()) {
    return fail("drum.orbit",
                "not with [[spray]] yet (droplets fly under a constant gravity, the carrier's "
                "field turns)");
  }
  return std::nullopt;
}

Problem check_drum(const SceneConfig& s) {
  const DrumConfig& d = s.drum;
  const double rmax = s.max_radius();
  if (auto p = positive("drum.diameter", d.diameter)) return p;
  if (!(d.diameter > 2.0 * rmax)) {
    return fail("drum.diameter",
                fmt::format("must exceed 2 * largest particle radius = {}", 2.0 * rmax));
  }
  if (auto p = positive("drum.depth", d.depth)) return p;
  if (!(d.depth > 2.0 * rmax)) {
    return fail("drum.depth",
                fmt::format("must exceed 2 * largest particle radius = {}", 2.0 * rmax));
  }
  if (!std::isfinite(d.omega)) {
    return fail("drum.omega", fmt::format("must be a finite number (rad/s), got {}", d.omega));
  }
  if (!(d.tilt >= 0.0 && d.tilt < 0.5 * std::numbers::pi)) {
    return fail("drum.tilt_deg",
                fmt::format("must be in [0, 90) degrees, got {}", tilt_in_degrees(d.tilt)));
  }
  return check_orbit(s);
}

Problem check_material(std::string_view table, const Material& m, bool with_density) {
  if (with_density) {
    if (auto reason = material_value_problem("density", m.density)) {
      return fail(fmt::format("{}.density", table), std::move(*reason));
    }
  }
  if (auto problem = material_problem(m)) {
    return fail(fmt::format("{}.{}", table, problem->key), std::move(problem->reason));
  }
  return std::nullopt;
}

Problem check_rolling(const ContactConfig& c) {
  if (c.rolling != RollingLaw::spring) return std::nullopt;
  if (c.normal != NormalLaw::linear_viscoelastic) {
    return fail(
        "contact.rolling",
        "\"spring\" needs normal = \"linear_viscoelastic\" (its k and gamma set k_r, gamma_r)");
  }
  if (auto p = positive("contact.rolling_stiffness_ratio", c.rolling_stiffness_ratio)) return p;
  return non_negative("contact.rolling_damping_ratio", c.rolling_damping_ratio);
}

Problem check_contact(const SceneConfig& s) {
  const ContactConfig& c = s.contact;
  if (auto p = check_rolling(c)) return p;
  if (c.normal == NormalLaw::linear)
    return positive("contact.linear_stiffness", c.linear_stiffness);
  if (c.normal != NormalLaw::linear_viscoelastic) return std::nullopt;
  if (auto p = positive("contact.collision_time", c.collision_time, " s")) return p;
  if (auto p = positive("contact.reference_radius", c.reference_radius, " m")) return p;
  if (auto p = positive("contact.tangential_stiffness_ratio", c.tangential_stiffness_ratio)) {
    return p;
  }
  return non_negative("contact.tangential_damping_ratio", c.tangential_damping_ratio);
}

/// A bridge of volume `v` reaches `rupture_distance(v)` beyond contact: every method's search
/// margin (and, at the wall, the wall candidates' reach). Bounded by kMaxRangeRadii smallest radii.
Problem check_bridge_reach(const SceneConfig& s, std::string key, double v) {
  if (s.classes.empty()) return std::nullopt;
  const LiquidConfig& l = s.liquid;
  constexpr double kDegree = std::numbers::pi / 180.0;
  const double theta =
      std::max(l.contact_angle_deg, l.wall_bridges ? l.wall_contact_angle_deg : 0.0) * kDegree;
  const BridgeLiquid liquid(l.surface_tension, theta);
  const double r_min = s.min_radius();
  const double reach = liquid.rupture_distance(v);
  const double limit = kMaxRangeRadii * r_min;
  if (reach <= limit) return std::nullopt;
  const double v_limit = std::pow(limit / (1.0 + 0.5 * theta), 3.0);
  return fail(
      std::move(key),
      fmt::format("a bridge of {} m^3 ruptures at a gap of {:.3g} m = {:.3g} smallest radii "
                  "(r = {} m), which every search method would take as its margin; at "
                  "most {} radii (a volume <= {:.3g} m^3) is allowed: is the volume in m^3?",
                  v, reach, reach / r_min, r_min, kMaxRangeRadii, v_limit));
}

Problem check_liquid_volumes(const SceneConfig& s) {
  const LiquidConfig& l = s.liquid;
  if (!l.migration) {
    if (auto p = positive("liquid.bridge_volume", l.bridge_volume, " (m^3)")) return p;
    return check_bridge_reach(s, "liquid.bridge_volume", l.bridge_volume);
  }
  if (!(l.liquid_content >= 0.0 && l.liquid_content <= 1.0)) {
    return fail(
        "liquid.liquid_content",
        fmt::format("must be in [0, 1] (liquid volume / solid volume), got {}", l.liquid_content));
  }
  if (auto p = non_negative("liquid.film_radius", l.film_radius)) return p;
  if (!(l.film_share >= 0.0 && l.film_share <= 1.0)) {
    return fail("liquid.film_share", fmt::format("must be in [0, 1], got {}", l.film_share));
  }
  if (!(l.rupture_to_bridges >= 0.0 && l.rupture_to_bridges <= 1.0)) {
    return fail("liquid.rupture_to_bridges",
                fmt::format("must be in [0, 1] (share of a ruptured bridge's halves that goes to "
                            "the particles' other bridges), got {}",
                            l.rupture_to_bridges));
  }
  if (auto p = positive("liquid.max_bridge_volume", l.max_bridge_volume, " (m^3)")) return p;
  return check_bridge_reach(s, "liquid.max_bridge_volume", l.max_bridge_volume);
}

/// A class's own liquid_content: a share of [liquid]'s films, so only with migration.
Problem check_class_liquid(const SceneConfig& s) {
  for (std::size_t i = 0; i < s.classes.size(); ++i) {
    const std::optional<double> content = s.classes[i].liquid_content;
    if (!content) continue;
    const std::string key = fmt::format("particles[{}].liquid_content", i);
    if (!s.liquid.enabled || !s.liquid.migration) {
      return fail(key, "needs [liquid] with liquid_content (the films that hold a class's liquid)");
    }
    if (!(*content >= 0.0 && *content <= 1.0)) {
      return fail(
          key, fmt::format("must be in [0, 1] (liquid volume / solid volume), got {}", *content));
    }
  }
  return std::nullopt;
}

Problem check_liquid(const SceneConfig& s) {
  const LiquidConfig& l = s.liquid;
  if (!l.enabled) return check_class_liquid(s);
  if (auto p = non_negative("liquid.surface_tension", l.surface_tension)) return p;
  if (auto p = angle_deg("liquid.contact_angle_deg", l.contact_angle_deg)) return p;
  if (auto p = non_negative("liquid.wall_surface_tension", l.wall_surface_tension)) return p;
  if (auto p = angle_deg("liquid.wall_contact_angle_deg", l.wall_contact_angle_deg)) return p;
  if (auto p = check_liquid_volumes(s)) return p;
  if (auto p = check_class_liquid(s)) return p;
  if (auto p = non_negative("liquid.viscosity", l.viscosity)) return p;
  if (l.viscosity > 0.0 && !(l.min_gap > 0.0)) {
    return fail("liquid.min_gap",
                fmt::format("must be > 0 (m) with viscosity > 0, got {}", l.min_gap));
  }
  return non_negative("liquid.min_gap", l.min_gap);
}

Problem check_cohesion(const SceneConfig& s) {
  if (!s.cohesion.enabled) return std::nullopt;
  return non_negative("cohesion.energy_density", s.cohesion.energy_density);
}

Problem check_spray(const SceneConfig& s, const SprayConfig& c, const std::string& key) {
  if (!s.liquid.enabled || !s.liquid.migration) {
    return fail(key,
                "needs [liquid] with liquid_content (the particles' films take the droplets; "
                "liquid_content = 0 for a dry powder)");
  }
  if (!c.position.allFinite()) return fail(key + ".position", "elements must be finite numbers");
  if (!c.direction.allFinite() || !(c.direction.norm() > 0.0)) {
    return fail(key + ".direction", "must be a finite vector of non-zero length");
  }
  if (!(c.angle_deg >= 0.0 && c.angle_deg < 180.0)) {
    return fail(key + ".angle_deg",
                fmt::format("must be in [0, 180) degrees, got {}", c.angle_deg));
  }
  if (c.shape == SprayShape::flat_fan) {
    const Vec3 d = c.direction.normalized();
    if (!c.fan_axis.allFinite() ||
        !((c.fan_axis - c.fan_axis.dot(d) * d).norm() > 1e-9 * c.fan_axis.norm())) {
      return fail(key + ".fan_axis", "must be a finite vector not parallel to direction");
    }
  }
  if (auto p = non_negative(key + ".rate", c.rate)) return p;
  if (auto p = non_negative(key + ".start", c.start)) return p;
  if (!(c.stop > c.start)) {
    return fail(key + ".stop", fmt::format("must be after start ({} s), got {}", c.start, c.stop));
  }
  if (auto p = positive(key + ".droplet_radius", c.droplet_radius, " m")) return p;
  if (c.droplet_radius > s.min_radius()) {
    return fail(key + ".droplet_radius",
                fmt::format("{} m is larger than the smallest particle ({} m): a droplet is "
                            "absorbed by particles larger than itself",
                            c.droplet_radius, s.min_radius()));
  }
  if (auto p = non_negative(key + ".droplet_speed", c.droplet_speed)) return p;
  const double radial = std::hypot(c.position.x(), c.position.y());
  const bool inside =
      radial + c.droplet_radius < 0.5 * s.drum.diameter &&
      (s.drum.ends == DrumEnds::periodic || (c.position.z() - c.droplet_radius > 0.0 &&
                                             c.position.z() + c.droplet_radius < s.drum.depth));
  if (!inside) {
    return fail(key + ".position",
                fmt::format("the nozzle [{}, {}, {}] is not inside the drum (radius {} m about the "
                            "z axis, z in [0, {}] m)",
                            c.position.x(), c.position.y(), c.position.z(), 0.5 * s.drum.diameter,
                            s.drum.depth));
  }
  return std::nullopt;
}

Problem check_sprays(const SceneConfig& s) {
  for (std::size_t i = 0; i < s.sprays.size(); ++i) {
    if (auto p = check_spray(s, s.sprays[i], fmt::format("spray[{}]", i))) return p;
  }
  return std::nullopt;
}

Problem check_fill(const SceneConfig& s) {
  const FillConfig& f = s.fill;
  switch (f.kind) {
    case FillKind::random:
      if (f.count < 1) return fail("fill.count", fmt::format("must be >= 1, got {}", f.count));
      if (f.count > 100'000'000) {
        return fail("fill.count", fmt::format("{} is more than 1e8 particles", f.count));
      }
      if (!(f.volume_fraction > 0.0 && f.volume_fraction <= 0.55)) {
        return fail(
            "fill.volume_fraction",
            fmt::format("must be in (0, 0.55] (loose random packing), got {}", f.volume_fraction));
      }
      break;
    case FillKind::paper_packing: {
      if (!(f.box.array() > 0.0).all() || !f.box.allFinite()) {
        return fail("fill.box", "all three sizes must be > 0");
      }
      const auto& c = s.classes;
      const bool single =
          std::none_of(c.begin(), c.end(), [](auto& k) { return k.polydisperse(); });
      if (c.size() != 3 || !single || !(c[0].radius < c[1].radius && c[1].radius < c[2].radius)) {
        return fail("fill.kind",
                    "\"paper_packing\" needs exactly three [[particles]] classes of one radius "
                    "each, small to large");
      }
      return std::nullopt;
    }
    case FillKind::file:
      if (f.file.empty()) return fail("fill.file", "must not be empty");
      break;
  }
  return non_negative("fill.settle_time", f.settle_time);
}

Problem check_time(const SceneConfig& s) {
  const TimeConfig& t = s.time;
  if (t.dt) {
    if (auto p = positive("time.dt", *t.dt)) return p;
  }
  if (!(t.dt_factor > 0.0 && t.dt_factor <= 1.0)) {
    return fail(
        "time.dt_factor",
        fmt::format("must be in (0, 1] (fraction of the Rayleigh time), got {}", t.dt_factor));
  }
  if (t.duration) {
    if (auto p = positive("time.duration", *t.duration)) return p;
  }
  if (t.revolutions) {
    if (auto p = positive("time.revolutions", *t.revolutions)) return p;
    if (s.drum.omega == 0.0) return fail("time.revolutions", "needs a turning drum (omega != 0)");
  }
  if (t.duration && t.revolutions) {
    return fail("time.revolutions", "give either duration or revolutions, not both");
  }
  if (!(t.max_overlap > 0.0 && t.max_overlap <= kMaxOverlapBound)) {
    return fail("time.max_overlap",
                fmt::format("must be in (0, {}] (radii of the smaller body), got {}",
                            kMaxOverlapBound, t.max_overlap));
  }
  if (s.dynamic() && !t.duration && !t.revolutions) {
    return fail("time.duration", "missing (run length: duration in s or revolutions)");
  }
  return std::nullopt;
}

Problem check_performance(const SceneConfig& s) {
  const double skin = s.performance.verlet_skin;
  if (!(skin > 0.0 && skin <= 10.0)) {
    return fail("performance.verlet_skin",
                fmt::format("must be in (0, 10] (units of the smallest radius), got {}", skin));
  }
  const std::uint64_t rows = s.performance.pair_block_rows;
  if (rows < static_cast<std::uint64_t>(kMinPairBlockRows) ||
      rows > static_cast<std::uint64_t>(kMaxPairBlockRows)) {
    return fail(
        "performance.pair_block_rows",
        fmt::format("must be in [{}, {}], got {}", kMinPairBlockRows, kMaxPairBlockRows, rows));
  }
  return std::nullopt;
}

Problem check_output(const SceneConfig& s) {
  if (s.output.directory.empty()) return fail("output.directory", "must not be empty");
  if (s.output.diagnostics_every < 1) {
    return fail("output.diagnostics_every",
                fmt::format("must be >= 1, got {}", s.output.diagnostics_every));
  }
  return std::nullopt;
}

std::string where_of(const SceneConfig& scene, std::string_view where) {
  if (!where.empty()) return std::string(where);
  if (!scene.source.empty()) return scene.source;
  return scene.name.empty() ? std::string("scene") : scene.name;
}

[[noreturn]] void throw_problem(const SceneConfig& scene, std::string_view where,
                                const SceneProblem& p) {
  throw InputError(fmt::format("{}: {}: {}", where_of(scene, where), p.key, p.reason));
}

}  // namespace

std::optional<SceneProblem> law_problem(const SceneConfig& scene) {
  if (auto p = check_material("material", scene.material, true)) return p;
  if (auto p = check_material("wall", scene.wall, false)) return p;
  if (auto p = check_contact(scene)) return p;
  if (auto p = check_liquid(scene)) return p;
  return check_cohesion(scene);
}

std::optional<SceneProblem> scene_problem(const SceneConfig& scene) {
  for (auto check : {check_top_level, check_classes, check_drum}) {
    if (auto p = check(scene)) return p;
  }
  if (auto p = law_problem(scene)) return p;
  if (auto p = mesh_wall_problem(scene)) return p;
  for (auto check : {check_sprays, check_fill, check_time, check_performance, check_output}) {
    if (auto p = check(scene)) return p;
  }
  return std::nullopt;
}

void validate(const SceneConfig& scene, std::string_view where) {
  if (const auto p = scene_problem(scene)) throw_problem(scene, where, *p);
}

void validate_laws(const SceneConfig& scene, std::string_view where) {
  if (const auto p = law_problem(scene)) throw_problem(scene, where, *p);
}

}  // namespace drumlab
