// SceneConfig -> a toml++ table -> TOML text by toml++'s formatter (keys of a table in
// alphabetical order, the tables after the top-level keys, [[particles]] last), then every float
// reprinted as the shortest decimal that parses back to the same bits: Debian's libtomlplusplus.so
// is built without TOML_FLOAT_CHARCONV and prints 17 significant digits (0.1 ->
// 0.10000000000000001), which a scene written for people must not show.
// tests/unit/test_scene_writer.cpp parses every written scene back.
#include "engine/scene/scene_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "engine/io/atomic_file.hpp"
#include "engine/scene/scene_validation.hpp"
#include "engine/types.hpp"

namespace drumlab {
namespace {

namespace fs = std::filesystem;

/// A float token of toml++'s output ("0.90000000000000002", "1e-09", "2600.0") as the shortest
/// decimal with the same bits; any other token (an integer, a boolean) as it is.
std::string shortest_float(std::string_view token) {
  if (token.find_first_of(".eEn") == std::string_view::npos) return std::string(token);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size()) return std::string(token);
  std::string text = fmt::format("{}", v);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";  // "n": inf, nan
  return text;
}

/// One line of toml++'s output with its float values reprinted: "key = VALUE" or
/// "key = [ V, V, V ]" where the value is not a string (a string, always quoted on one line,
/// is left alone), table headers and blank lines as they are.
std::string shortest_floats(const std::string& line) {
  const std::size_t eq = line.find(" = ");
  if (eq == std::string::npos || line.compare(eq + 3, 1, "\"") == 0) return line;
  std::string out = line.substr(0, eq + 3);
  std::string_view value = std::string_view(line).substr(eq + 3);
  const bool array = value.size() >= 4 && value.starts_with("[ ") && value.ends_with(" ]");
  if (array) value = value.substr(2, value.size() - 4);
  std::string items;
  for (std::size_t begin = 0; begin <= value.size();) {
    const std::size_t comma = std::min(value.find(", ", begin), value.size());
    items += (begin == 0 ? "" : ", ") + shortest_float(value.substr(begin, comma - begin));
    begin = comma + 2;
  }
  return out + (array ? "[ " + items + " ]" : items);
}

toml::array vec3(const Vec3& v) {
  return toml::array{v.x(), v.y(), v.z()};
}

/// A TOML integer (int64); throws for values the loader could not read back.
std::int64_t integer(std::uint64_t v, std::string_view key) {
  if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    throw InputError(fmt::format("{}: {} does not fit a TOML integer", key, v));
  }
  return static_cast<std::int64_t>(v);
}

/// `file` relative to `folder` when both resolve under one root, else absolute.
fs::path relative_path(const fs::path& file, const fs::path& folder) {
  const fs::path base = folder.empty() ? fs::current_path() : fs::absolute(folder);
  fs::path dir = base.lexically_normal();
  if (!dir.has_filename() && dir.has_relative_path()) dir = dir.parent_path();  // trailing '/'
  const fs::path target = fs::absolute(file).lexically_normal();
  const fs::path rel = target.lexically_relative(dir);
  return rel.empty() ? target : rel;
}

toml::table drum_table(const DrumConfig& d) {
  toml::table t{{"diameter", d.diameter},
                {"depth", d.depth},
                {"tilt_deg", tilt_in_degrees(d.tilt)},
                {"ends", d.ends == DrumEnds::periodic ? "periodic" : "caps"}};
  const DrumOrbit& o = d.orbit;
  if (!o.speed_ratio) t.insert("omega", d.omega);
  if (o.active() || o.speed_ratio) {
    toml::table orbit{{"radius", o.radius}, {"omega", o.omega}};
    if (o.phase != 0.0) orbit.insert("phase_deg", tilt_in_degrees(o.phase));
    if (o.speed_ratio) orbit.insert("speed_ratio", *o.speed_ratio);
    t.insert("orbit", std::move(orbit));
  }
  return t;
}

toml::array particles_array(const std::vector<ParticleClass>& classes) {
  toml::array out;
  for (const ParticleClass& c : classes) {
    toml::table t{{"name", c.name}, {"volume_fraction", c.volume_fraction}};
    if (c.distribution != SizeKind::single)
      t.insert("distribution", size_kind_name(c.distribution));
    if (c.distribution == SizeKind::table) {
      toml::array radii, shares;
      for (const double r : c.radii) radii.push_back(r);
      for (const double w : c.shares) shares.push_back(w);
      t.insert("radii", std::move(radii));
      t.insert("shares", std::move(shares));
    } else {
      t.insert("radius", c.radius);
    }
    if (c.distribution == SizeKind::normal || c.distribution == SizeKind::lognormal) {
      t.insert("radius_sigma", c.radius_sigma);
      t.insert("truncate", c.truncate);
    }
    if (c.liquid_content) t.insert("liquid_content", *c.liquid_content);
    out.push_back(std::move(t));
  }
  return out;
}

toml::table material_table(const Material& m) {
  return toml::table{{"density", m.density},
                     {"youngs_modulus", m.youngs_modulus},
                     {"poisson_ratio", m.poisson_ratio},
                     {"restitution", m.restitution},
                     {"friction", m.friction},
                     {"rolling_friction", m.rolling_friction}};
}

/// The [wall] keys that differ from [material] (each defaults to it); empty when none does.
toml::table wall_table(const Material& wall, const Material& m) {
  toml::table t;
  auto differing = [&](std::string_view key, double value, double material_value) {
    if (value != material_value) t.insert(key, value);
  };
  differing("youngs_modulus", wall.youngs_modulus, m.youngs_modulus);
  differing("poisson_ratio", wall.poisson_ratio, m.poisson_ratio);
  differing("restitution", wall.restitution, m.restitution);
  differing("friction", wall.friction, m.friction);
  differing("rolling_friction", wall.rolling_friction, m.rolling_friction);
  return t;
}

/// A mesh's material keys that differ from [wall]'s (each defaults to it).
void insert_mesh_material(toml::table& t, const MeshMaterial& m, const Material& wall) {
  auto differing = [&](std::string_view key, double value, double wall_value) {
    if (value != wall_value) t.insert(key, value);
  };
  differing("youngs_modulus", m.youngs_modulus, wall.youngs_modulus);
  differing("poisson_ratio", m.poisson_ratio, wall.poisson_ratio);
  differing("restitution", m.restitution, wall.restitution);
  differing("friction", m.friction, wall.friction);
  differing("rolling_friction", m.rolling_friction, wall.rolling_friction);
}

toml::array mesh_array(const SceneConfig& s, const fs::path& folder) {
  toml::array out;
  for (const MeshWallConfig& c : s.meshes) {
    toml::table t{{"file", relative_path(c.file, folder).generic_string()},
                  {"scale", c.scale},
                  {"offset", vec3(c.offset)},
                  {"rotation_deg", vec3(c.rotation_deg)},
                  {"attach", c.attach == MeshAttach::lab ? "lab" : "drum"},
                  {"smooth_angle_deg", c.smooth_angle_deg},
                  {"closed", c.closed}};
    insert_mesh_material(t, c.material, s.wall);
    out.push_back(std::move(t));
  }
  return out;
}

toml::array lifter_array(const SceneConfig& s) {
  toml::array out;
  for (const LifterWallConfig& c : s.lifters) {
    toml::table t{{"count", c.count},
                  {"height", c.height},
                  {"length", c.length},
                  {"thickness", c.thickness},
                  {"shape", c.shape == LifterKind::angled ? "angled" : "straight"},
                  {"phase_deg", c.phase_deg}};
    if (c.shape == LifterKind::angled) {
      t.insert("angle_deg", c.angle_deg);
      t.insert("tip", c.tip);
    }
    insert_mesh_material(t, c.material, s.wall);
    out.push_back(std::move(t));
  }
  return out;
}

toml::table contact_normal_table(const ContactConfig& c) {
  if (c.normal == NormalLaw::linear) {
    return toml::table{{"normal", "linear"}, {"linear_stiffness", c.linear_stiffness}};
  }
  if (c.normal == NormalLaw::linear_viscoelastic) {
    return toml::table{{"normal", "linear_viscoelastic"},
                       {"collision_time", c.collision_time},
                       {"reference_radius", c.reference_radius},
                       {"tangential_stiffness_ratio", c.tangential_stiffness_ratio},
                       {"tangential_damping_ratio", c.tangential_damping_ratio}};
  }
  return toml::table{{"normal", "hertz"}};
}

toml::table contact_table(const ContactConfig& c) {
  toml::table t = contact_normal_table(c);
  if (c.rolling == RollingLaw::spring) {
    t.insert("rolling", "spring");
    t.insert("rolling_stiffness_ratio", c.rolling_stiffness_ratio);
    t.insert("rolling_damping_ratio", c.rolling_damping_ratio);
  }
  return t;
}

toml::array spray_array(const std::vector<SprayConfig>& sprays) {
  toml::array out;
  for (const SprayConfig& c : sprays) {
    toml::table t{{"name", c.name},
                  {"position", vec3(c.position)},
                  {"direction", vec3(c.direction)},
                  {"shape", c.shape == SprayShape::flat_fan ? "flat_fan" : "cone"},
                  {"angle_deg", c.angle_deg},
                  {"rate", c.rate},
                  {"start", c.start},
                  {"droplet_radius", c.droplet_radius},
                  {"droplet_speed", c.droplet_speed}};
    if (c.shape == SprayShape::flat_fan) t.insert("fan_axis", vec3(c.fan_axis));
    if (std::isfinite(c.stop)) t.insert("stop", c.stop);
    if (c.at_wall == SprayAtWall::wet) t.insert("at_wall", "wet");
    out.push_back(std::move(t));
  }
  return out;
}

toml::table liquid_table(const LiquidConfig& l) {
  toml::table t{{"surface_tension", l.surface_tension},
                {"contact_angle_deg", l.contact_angle_deg},
                {"wall_bridges", l.wall_bridges},
                {"wall_surface_tension", l.wall_surface_tension},
                {"wall_contact_angle_deg", l.wall_contact_angle_deg}};
  if (l.migration) {
    t.insert("liquid_content", l.liquid_content);
    t.insert("film_share", l.film_share);
    t.insert("max_bridge_volume", l.max_bridge_volume);
    if (l.film_radius > 0.0) t.insert("film_radius", l.film_radius);
    if (l.proportional_draw) t.insert("bridge_draw", "proportional");
    if (l.rupture_to_bridges > 0.0) t.insert("rupture_to_bridges", l.rupture_to_bridges);
  } else {
    t.insert("bridge_volume", l.bridge_volume);
  }
  if (l.viscosity > 0.0) {
    t.insert("viscosity", l.viscosity);
    t.insert("min_gap", l.min_gap);
  }
  return t;
}

toml::table fill_table(const FillConfig& f, const fs::path& folder) {
  switch (f.kind) {
    case FillKind::random:
      return toml::table{{"kind", "random"},
                         {"count", integer(f.count, "fill.count")},
                         {"volume_fraction", f.volume_fraction},
                         {"seed", integer(f.seed, "fill.seed")},
                         {"settle_time", f.settle_time}};
    case FillKind::file:
      return toml::table{{"kind", "file"},
                         {"file", relative_path(f.file, folder).generic_string()},
                         {"settle_time", f.settle_time}};
    case FillKind::paper_packing:
      break;
  }
  return toml::table{{"kind", "paper_packing"}, {"box", vec3(f.box)}};
}

toml::table time_table(const TimeConfig& t) {
  toml::table out;
  if (t.dt) {
    out.insert("dt", *t.dt);
  } else {
    out.insert("dt_factor", t.dt_factor);
  }
  if (t.duration) out.insert("duration", *t.duration);
  if (t.revolutions) out.insert("revolutions", *t.revolutions);
  out.insert("max_overlap", t.max_overlap);
  return out;
}

toml::table output_table(const SceneConfig& s) {
  toml::table t{
      {"diagnostics_every", integer(s.output.diagnostics_every, "output.diagnostics_every")}};
  if (s.output.directory != default_output_directory(s.name)) {
    t.insert("directory", s.output.directory);
  }
  return t;
}

toml::table scene_table(const SceneConfig& s, const fs::path& folder) {
  toml::table t{
      {"name", s.name},
      {"description", s.description},
      {"gravity", vec3(s.gravity)},
      {"search", s.search_method},
      {"drum", drum_table(s.drum)},
      {"particles", particles_array(s.classes)},
      {"material", material_table(s.material)},
      {"contact", contact_table(s.contact)},
      {"fill", fill_table(s.fill, folder)},
      {"time", time_table(s.time)},
      {"performance",
       toml::table{{"verlet_skin", s.performance.verlet_skin},
                   {"sort_every", integer(s.performance.sort_every, "performance.sort_every")},
                   {"pair_block_rows",
                    integer(s.performance.pair_block_rows, "performance.pair_block_rows")}}},
      {"output", output_table(s)}};
  toml::table wall = wall_table(s.wall, s.material);
  if (!s.meshes.empty()) wall.insert("mesh", mesh_array(s, folder));
  if (!s.lifters.empty()) wall.insert("lifters", lifter_array(s));
  if (!wall.empty()) t.insert("wall", std::move(wall));
  if (s.liquid.enabled) t.insert("liquid", liquid_table(s.liquid));
  if (!s.sprays.empty()) t.insert("spray", spray_array(s.sprays));
  if (s.cohesion.enabled) {
    t.insert("cohesion",
             toml::table{{"model", "sjkr"}, {"energy_density", s.cohesion.energy_density}});
  }
  return t;
}

}  // namespace

std::string scene_to_toml(const SceneConfig& scene, const fs::path& folder) {
  std::ostringstream toml_text;
  toml_text << toml::toml_formatter(scene_table(scene, folder),
                                    toml::format_flags::allow_unicode_strings);
  return "# Written by drumlab (engine/scene/scene_writer.cpp); keys: scenes/README.md.\n\n" +
         with_shortest_floats(toml_text.str());
}

std::string with_shortest_floats(const std::string& toml_text) {
  std::string out;
  std::istringstream lines(toml_text);
  for (std::string line; std::getline(lines, line);) out += shortest_floats(line) + '\n';
  return out;
}

std::string scene_to_toml(const SceneConfig& scene) {
  return scene_to_toml(scene, fs::path(scene.source).parent_path());
}

void save_scene(const SceneConfig& scene, const fs::path& file) {
  validate(scene, fmt::format("{} not saved", file.string()));
  std::string text;
  try {
    text = scene_to_toml(scene, file.parent_path());
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", file.string(), e.what()));
  }
  write_file_atomically(file, [&](std::ostream& out) { out << text; });
}

}  // namespace drumlab
