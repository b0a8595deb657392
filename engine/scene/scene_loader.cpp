// Reads scenes/*.toml into a SceneConfig. Every problem is reported as one line
// "<file>: <key>: <reason>" in an InputError; the key is the dotted path in the file
// (e.g. "drum.diameter", "particles[1].radius"). The schema is documented in the header comment of
// every shipped scene file (see scenes/drum_demo.toml).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "engine/mesh/wall_meshes.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/scene/scene_validation.hpp"
#include "engine/search/contact_search.hpp"

namespace drumlab {
namespace {

std::string_view type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
      return "a date/time";
    default:
      return "nothing";
  }
}

/// One TOML table of the scene with its dotted path, for typed reads and one-line errors.
class Scope {
 public:
  Scope(const toml::table& table, std::string path, const std::string& source)
      : table_(&table), path_(std::move(path)), source_(&source) {}

  std::string key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
  }

  /// Throws "<file>: <path.key>: <reason> (line N)".
  [[noreturn]] void fail(std::string_view key, std::string_view reason) const {
    const toml::node* node = key.empty() ? table_ : table_->get(key);
    const std::string where = key.empty() ? path_ : key_path(key);
    const auto line = node ? node->source().begin.line : 0;
    if (line > 0) {
      throw InputError(fmt::format("{}: {}: {} (line {})", *source_, where, reason, line));
    }
    throw InputError(fmt::format("{}: {}: {}", *source_, where, reason));
  }

  [[noreturn]] void missing(std::string_view key, std::string_view what) const {
    throw InputError(
        fmt::format("{}: {}: missing required key ({})", *source_, key_path(key), what));
  }

  /// Rejects any key not in `allowed`, naming it and listing the valid ones.
  void allow_only(std::initializer_list<std::string_view> allowed) const {
    for (auto&& [key, node] : *table_) {
      bool known = false;
      for (auto a : allowed) known = known || a == key.str();
      if (!known) {
        fail(key.str(), fmt::format("unknown key (valid here: {})", fmt::join(allowed, ", ")));
      }
    }
  }

  bool has(std::string_view key) const { return table_->contains(key); }

  std::optional<double> number(std::string_view key) const {
    const toml::node* node = table_->get(key);
    if (!node) return std::nullopt;
    double value = 0.0;
    if (auto i = node->as_integer()) {
      value = static_cast<double>(i->get());
    } else if (auto f = node->as_floating_point()) {
      value = f->get();
    } else {
      fail(key, fmt::format("expected a number, got {}", type_name(*node)));
    }
    if (!std::isfinite(value)) fail(key, "must be a finite number");
    return value;
  }

  double number_or(std::string_view key, double fallback) const {
    return number(key).value_or(fallback);
  }

  double required_number(std::string_view key, std::string_view what) const {
    if (auto v = number(key)) return *v;
    missing(key, what);
  }

  std::optional<std::int64_t> integer(std::string_view key) const {
    const toml::node* node = table_->get(key);
    if (!node) return std::nullopt;
    if (auto i = node->as_integer()) return i->get();
    fail(key, fmt::format("expected an integer, got {}", type_name(*node)));
  }

  std::optional<std::string> string(std::string_view key) const {
    const toml::node* node = table_->get(key);
    if (!node) return std::nullopt;
    if (auto s = node->as_string()) return s->get();
    fail(key, fmt::format("expected a string, got {}", type_name(*node)));
  }

  std::optional<Vec3> vec3(std::string_view key) const {
    const toml::node* node = table_->get(key);
    if (!node) return std::nullopt;
    const toml::array* array = node->as_array();
    if (!array)
      fail(key, fmt::format("expected an array of three numbers, got {}", type_name(*node)));
    if (array->size() != 3) {
      fail(key, fmt::format("expected an array of three numbers, got {} elements", array->size()));
    }
    Vec3 v;
    for (int k = 0; k < 3; ++k) {
      const toml::node& item = (*array)[static_cast<std::size_t>(k)];
      if (auto i = item.as_integer()) {
        v[k] = static_cast<double>(i->get());
      } else if (auto f = item.as_floating_point()) {
        v[k] = f->get();
      } else {
        fail(key, fmt::format("element {} must be a number, got {}", k, type_name(item)));
      }
    }
    if (!v.allFinite()) fail(key, "elements must be finite numbers");
    return v;
  }

  /// A required array of numbers (may be empty: validation says what it needs).
  std::vector<double> numbers(std::string_view key, std::string_view what) const {
    const toml::node* node = table_->get(key);
    if (!node) missing(key, what);
    const toml::array* array = node->as_array();
    if (!array) fail(key, fmt::format("expected an array of numbers, got {}", type_name(*node)));
    std::vector<double> out;
    for (const toml::node& item : *array) {
      if (auto i = item.as_integer()) {
        out.push_back(static_cast<double>(i->get()));
      } else if (auto f = item.as_floating_point()) {
        out.push_back(f->get());
      } else {
        fail(key, fmt::format("element {} must be a number, got {}", out.size(), type_name(item)));
      }
    }
    return out;
  }

  /// A sub-table, or nullopt when absent; any other type is an error.
  std::optional<Scope> table(std::string_view key) const {
    const toml::node* node = table_->get(key);
    if (!node) return std::nullopt;
    if (auto t = node->as_table()) return Scope(*t, key_path(key), *source_);
    fail(key, fmt::format("expected a table [{}], got {}", key_path(key), type_name(*node)));
  }

  Scope required_table(std::string_view key) const {
    if (auto t = table(key)) return *t;
    throw InputError(
        fmt::format("{}: {}: missing required table [{}]", *source_, key_path(key), key_path(key)));
  }

  const toml::table& raw() const { return *table_; }
  const std::string& source() const { return *source_; }

 private:
  const toml::table* table_;
  std::string path_;
  const std::string* source_;
};

// ---- sections --------------------------------------------------------------------------------

/// Reads the keys of a material table; `base` supplies values for omitted keys when
/// `all_optional` (the [wall] table), otherwise the core keys are required.
Material read_material(const Scope& s, const Material& base, bool all_optional) {
  Material m = base;
  auto get = [&](std::string_view key, double fallback, std::string_view what) {
    if (all_optional) return s.number_or(key, fallback);
    return s.required_number(key, what);
  };
  if (!all_optional) m.density = get("density", m.density, "kg/m^3");
  m.youngs_modulus = get("youngs_modulus", m.youngs_modulus, "Young's modulus E, Pa");
  m.poisson_ratio = get("poisson_ratio", m.poisson_ratio, "Poisson ratio nu");
  m.restitution = get("restitution", m.restitution, "coefficient of restitution e");
  m.friction = get("friction", m.friction, "sliding friction coefficient mu");
  m.rolling_friction = s.number_or("rolling_friction", all_optional ? m.rolling_friction : 0.0);
  return m;
}

/// The keys of a class's size: `radius` alone, or a distribution (scene_validation checks the
/// values; here only which keys go with which kind).
void read_size(const Scope& s, ParticleClass& c) {
  if (const auto name = s.string("distribution")) {
    const auto kind = parse_size_kind(*name);
    if (!kind) {
      s.fail("distribution",
             fmt::format("unknown distribution \"{}\" (valid: normal, lognormal, table)", *name));
    }
    c.distribution = *kind;
  }
  const bool spread = c.distribution == SizeKind::normal || c.distribution == SizeKind::lognormal;
  const bool table = c.distribution == SizeKind::table;
  for (const std::string_view key : {"radius_sigma", "truncate"}) {
    if (s.has(key) && !spread) {
      s.fail(key, "only with distribution = \"normal\" or \"lognormal\"");
    }
  }
  for (const std::string_view key : {"radii", "shares"}) {
    if (s.has(key) && !table) s.fail(key, "only with distribution = \"table\"");
  }
  if (table) {
    if (s.has("radius")) s.fail("radius", "not with distribution = \"table\" (radii gives them)");
    c.radii = s.numbers("radii", "the table's radii, m");
    c.shares = s.numbers("shares", "number share of each radius");
    return;
  }
  c.radius = s.required_number("radius", spread ? "mean particle radius, m" : "particle radius, m");
  if (spread) {
    c.radius_sigma = s.required_number("radius_sigma", "standard deviation of the radius, m");
    c.truncate = s.number_or("truncate", kDefaultTruncate);
  }
}

void read_particles(const Scope& root, SceneConfig& scene) {
  const toml::node* node = root.raw().get("particles");
  if (!node) root.missing("particles", "one [[particles]] table per size class");
  const toml::array* array = node->as_array();
  if (!array || !array->is_array_of_tables()) {
    root.fail("particles",
              fmt::format("expected an array of tables [[particles]], got {}", type_name(*node)));
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    const Scope s(*(*array)[i].as_table(), fmt::format("particles[{}]", i), root.source());
    s.allow_only({"name", "radius", "volume_fraction", "distribution", "radius_sigma", "truncate",
                  "radii", "shares", "liquid_content"});
    ParticleClass c;
    c.name = s.string("name").value_or(fmt::format("class{}", i));
    read_size(s, c);
    c.liquid_content = s.number("liquid_content");
    if (array->size() == 1) {
      c.volume_fraction = s.number_or("volume_fraction", 1.0);
    } else {
      c.volume_fraction = s.required_number("volume_fraction", "share of the solid volume");
    }
    scene.classes.push_back(c);
  }
}

// [drum.orbit]: the planetary carrier (scene_config.hpp, DrumOrbit).
// An angular velocity given as `omega` (rad/s) or `rpm` (not both), in rad/s; nullopt for neither.
std::optional<double> angular_velocity(const Scope& s) {
  const auto omega = s.number("omega");
  const auto rpm = s.number("rpm");
  if (omega && rpm) s.fail("rpm", "give either omega (rad/s) or rpm, not both");
  if (rpm) return *rpm * 2.0 * std::numbers::pi / 60.0;
  return omega;
}

void read_orbit(const Scope& s, DrumOrbit& o) {
  s.allow_only({"radius", "omega", "rpm", "phase_deg", "speed_ratio"});
  o.radius = s.required_number("radius", "the drum axis's distance from the central axis, m");
  const auto omega = angular_velocity(s);
  if (!omega) s.missing("omega", "the carrier's angular velocity: omega in rad/s or rpm");
  o.omega = *omega;
  o.phase = tilt_from_degrees(s.number_or("phase_deg", 0.0));
  o.speed_ratio = s.number("speed_ratio");
}

void read_drum(const Scope& root, SceneConfig& scene) {
  const Scope s = root.required_table("drum");
  s.allow_only({"diameter", "depth", "omega", "rpm", "tilt_deg", "ends", "orbit"});
  DrumConfig& d = scene.drum;
  d.diameter = s.required_number("diameter", "drum diameter D, m");
  d.depth = s.required_number("depth", "drum depth H along the axis, m");
  const auto omega = angular_velocity(s);
  if (const auto orbit = s.table("orbit")) read_orbit(*orbit, d.orbit);
  if (d.orbit.speed_ratio) {
    if (omega) {
      s.fail(s.has("omega") ? "omega" : "rpm",
             "give the drum's rate either here (absolute) or as orbit.speed_ratio, not both");
    }
    d.omega = d.orbit.omega * (1.0 + *d.orbit.speed_ratio);
  } else {
    if (!omega) s.missing("omega", "drum angular velocity: omega in rad/s or rpm");
    d.omega = *omega;
  }
  d.tilt = tilt_from_degrees(s.number_or("tilt_deg", 0.0));
  const std::string ends = s.string("ends").value_or("caps");
  if (ends == "caps") {
    d.ends = DrumEnds::caps;
  } else if (ends == "periodic") {
    d.ends = DrumEnds::periodic;
  } else {
    s.fail("ends", fmt::format("unknown value '{}' (valid: caps, periodic)", ends));
  }
}

void read_linear_viscoelastic(const Scope& s, ContactConfig& c) {
  c.normal = NormalLaw::linear_viscoelastic;
  c.collision_time = s.required_number("collision_time", "collision time of the reference pair, s");
  c.reference_radius = s.required_number(
      "reference_radius", "radius of the reference pair's spheres (e.g. the mean radius), m");
  c.tangential_stiffness_ratio =
      s.number_or("tangential_stiffness_ratio", c.tangential_stiffness_ratio);
  c.tangential_damping_ratio = s.number_or("tangential_damping_ratio", c.tangential_damping_ratio);
}

// [contact] rolling = "constant_torque" (default) | "spring", with the spring's ratios.
void read_rolling(const Scope& s, ContactConfig& c) {
  const std::string rolling = s.string("rolling").value_or("constant_torque");
  if (rolling == "spring") {
    c.rolling = RollingLaw::spring;
    c.rolling_stiffness_ratio = s.number_or("rolling_stiffness_ratio", c.rolling_stiffness_ratio);
    c.rolling_damping_ratio = s.number_or("rolling_damping_ratio", c.rolling_damping_ratio);
    return;
  }
  if (rolling != "constant_torque") {
    s.fail("rolling", fmt::format("unknown value '{}' (valid: constant_torque, spring)", rolling));
  }
  for (const char* key : {"rolling_stiffness_ratio", "rolling_damping_ratio"}) {
    if (s.has(key)) s.fail(key, "only used with rolling = \"spring\"");
  }
}

void read_contact(const Scope& root, SceneConfig& scene) {
  const auto s = root.table("contact");
  if (!s) return;
  s->allow_only({"normal", "linear_stiffness", "collision_time", "reference_radius",
                 "tangential_stiffness_ratio", "tangential_damping_ratio", "rolling",
                 "rolling_stiffness_ratio", "rolling_damping_ratio"});
  read_rolling(*s, scene.contact);
  const std::string normal = s->string("normal").value_or("hertz");
  if (normal != "linear_viscoelastic") {
    for (const char* key : {"collision_time", "reference_radius", "tangential_stiffness_ratio",
                            "tangential_damping_ratio"}) {
      if (s->has(key)) s->fail(key, "only used with normal = \"linear_viscoelastic\"");
    }
  }
  if (normal == "hertz") {
    scene.contact.normal = NormalLaw::hertz;
    if (s->has("linear_stiffness")) {
      s->fail("linear_stiffness", "only used with normal = \"linear\"");
    }
  } else if (normal == "linear") {
    scene.contact.normal = NormalLaw::linear;
    scene.contact.linear_stiffness =
        s->required_number("linear_stiffness", "normal spring stiffness of the linear law, N/m");
  } else if (normal == "linear_viscoelastic") {
    if (s->has("linear_stiffness")) {
      s->fail("linear_stiffness", "only used with normal = \"linear\"");
    }
    read_linear_viscoelastic(*s, scene.contact);
  } else {
    s->fail("normal",
            fmt::format("unknown value '{}' (valid: hertz, linear, linear_viscoelastic)", normal));
  }
}

void read_random_fill(const Scope& s, FillConfig& f) {
  s.allow_only({"kind", "count", "volume_fraction", "seed", "settle_time"});
  const auto count = s.integer("count");
  if (!count) s.missing("count", "total number of particles");
  if (*count <= 0) s.fail("count", fmt::format("must be >= 1, got {}", *count));
  f.count = static_cast<std::size_t>(*count);
  f.volume_fraction = s.number_or("volume_fraction", f.volume_fraction);
  const std::int64_t seed = s.integer("seed").value_or(static_cast<std::int64_t>(f.seed));
  if (seed < 0) s.fail("seed", fmt::format("must be >= 0, got {}", seed));
  f.seed = static_cast<std::uint64_t>(seed);
  f.settle_time = s.number_or("settle_time", f.settle_time);
}

void read_paper_fill(const Scope& s, SceneConfig& scene) {
  s.allow_only({"kind", "box"});
  const auto box = s.vec3("box");
  if (!box) s.missing("box", "[x, y, z] size of the packing box, m");
  scene.fill.box = *box;
  scene.fill.count = 0;
}

/// [fill] kind = "file": the CSV path relative to the scene file's folder. The file itself is read
/// by file_fill (engine/fill/file_fill.hpp); here only that it exists.
void read_file_fill(const Scope& s, SceneConfig& scene) {
  s.allow_only({"kind", "file", "settle_time"});
  const auto file = s.string("file");
  if (!file) s.missing("file", "CSV of the initial particles x,y,z,r[,vx,vy,vz], m and m/s");
  if (file->empty()) s.fail("file", "must not be empty");  // before it becomes the folder
  std::filesystem::path path(*file);
  if (path.is_relative()) path = std::filesystem::path(scene.source).parent_path() / path;
  path = path.lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    s.fail("file", fmt::format("cannot read particle file {}", path.string()));
  }
  scene.fill.file = path;
  scene.fill.count = 0;  // known once the file is read
  scene.fill.settle_time = s.number_or("settle_time", scene.fill.settle_time);
}

void read_fill(const Scope& root, SceneConfig& scene) {
  const Scope s = root.required_table("fill");
  const std::string kind = s.string("kind").value_or("random");
  if (kind == "random") {
    scene.fill.kind = FillKind::random;
    read_random_fill(s, scene.fill);
  } else if (kind == "paper_packing") {
    scene.fill.kind = FillKind::paper_packing;
    read_paper_fill(s, scene);
  } else if (kind == "file") {
    scene.fill.kind = FillKind::file;
    read_file_fill(s, scene);
  } else {
    s.fail("kind", fmt::format("unknown value '{}' (valid: random, file, paper_packing)", kind));
  }
}

void read_time(const Scope& root, SceneConfig& scene) {
  const auto s = root.table("time");
  const bool dynamic = scene.dynamic();
  if (!s) {
    if (dynamic) root.missing("time", "[time] with duration or revolutions");
    return;
  }
  s->allow_only({"dt", "dt_factor", "duration", "revolutions", "max_overlap"});
  TimeConfig& t = scene.time;
  if (s->has("dt") && s->has("dt_factor")) s->fail("dt_factor", "give either dt or dt_factor");
  t.dt = s->number("dt");
  t.dt_factor = s->number_or("dt_factor", t.dt_factor);
  if (s->has("duration") && s->has("revolutions")) {
    s->fail("revolutions", "give either duration or revolutions, not both");
  }
  t.duration = s->number("duration");
  t.revolutions = s->number("revolutions");
  t.max_overlap = s->number_or("max_overlap", t.max_overlap);
  if (dynamic && !t.duration && !t.revolutions) {
    s->missing("duration", "run length: duration in s or revolutions");
  }
}

void read_output(const Scope& root, SceneConfig& scene) {
  scene.output.directory = default_output_directory(scene.name);
  const auto s = root.table("output");
  if (!s) return;
  s->allow_only({"directory", "diagnostics_every"});
  scene.output.directory = s->string("directory").value_or(scene.output.directory);
  const std::int64_t every = s->integer("diagnostics_every").value_or(1000);
  if (every < 1) s->fail("diagnostics_every", fmt::format("must be >= 1, got {}", every));
  scene.output.diagnostics_every = static_cast<std::uint64_t>(every);
}

// [liquid]: Willett's closed form holds for 0 <= theta < 90 degrees (cos theta > 0: a bridge that
// pulls); the liquid is given as one fixed bridge volume or as a content with films (migration).
void read_liquid(const Scope& root, SceneConfig& scene) {
  const auto s = root.table("liquid");
  if (!s) return;
  s->allow_only({"surface_tension", "contact_angle_deg", "bridge_volume", "liquid_content",
                 "film_share", "max_bridge_volume", "film_radius", "bridge_draw",
                 "rupture_to_bridges", "viscosity", "min_gap", "wall_bridges",
                 "wall_surface_tension", "wall_contact_angle_deg"});
  LiquidConfig& l = scene.liquid;
  l.enabled = true;
  l.surface_tension = s->required_number("surface_tension", "N/m, > 0");
  l.contact_angle_deg = s->number_or("contact_angle_deg", 0.0);
  l.wall_surface_tension = s->number_or("wall_surface_tension", l.surface_tension);
  l.wall_contact_angle_deg = s->number_or("wall_contact_angle_deg", l.contact_angle_deg);
  if (const toml::node* w = s->raw().get("wall_bridges")) {
    if (!w->as_boolean()) s->fail("wall_bridges", "expected true or false");
    l.wall_bridges = w->as_boolean()->get();
  }
  l.migration = s->has("liquid_content");
  if (s->has("bridge_volume") && l.migration) {
    s->fail("bridge_volume",
            "give either bridge_volume (fixed bridges) or liquid_content with max_bridge_volume "
            "(liquid migration), not both");
  }
  if (!l.migration) {
    l.bridge_volume = s->required_number(
        "bridge_volume", "m^3, > 0; or liquid_content with max_bridge_volume for migration");
    for (const char* key :
         {"film_share", "max_bridge_volume", "film_radius", "bridge_draw", "rupture_to_bridges"}) {
      if (s->has(key)) s->fail(key, "only with liquid_content (liquid migration)");
    }
  } else {
    l.liquid_content = s->required_number("liquid_content", "liquid / solid volume, >= 0");
    l.film_share = s->number_or("film_share", 1.0);
    l.max_bridge_volume = s->required_number("max_bridge_volume", "m^3, > 0");
    l.film_radius = s->number_or("film_radius", 0.0);
    const std::string draw = s->string("bridge_draw").value_or("halves");
    if (draw != "halves" && draw != "proportional") {
      s->fail("bridge_draw", fmt::format("unknown value '{}' (valid: halves, proportional)", draw));
    }
    l.proportional_draw = draw == "proportional";
    l.rupture_to_bridges = s->number_or("rupture_to_bridges", 0.0);
  }
  l.viscosity = s->number_or("viscosity", 0.0);
  l.min_gap = s->number_or("min_gap", 0.0);
  if (l.viscosity == 0.0 && s->has("min_gap")) s->fail("min_gap", "only with viscosity > 0");
}

// [cohesion]: LIGGGHTS' simplified JKR, the only dry adhesion law for now.
void read_cohesion(const Scope& root, SceneConfig& scene) {
  const auto s = root.table("cohesion");
  if (!s) return;
  s->allow_only({"model", "energy_density"});
  const std::string model = s->string("model").value_or("sjkr");
  if (model != "sjkr") s->fail("model", fmt::format("unknown model '{}' (valid: sjkr)", model));
  scene.cohesion.enabled = true;
  scene.cohesion.energy_density = s->required_number("energy_density", "k_c, J/m^3, >= 0");
}

// [[spray]]: nozzles of binder (engine/spray/spray_config.hpp); the validation checks the values.
void read_sprays(const Scope& root, SceneConfig& scene) {
  const toml::node* node = root.raw().get("spray");
  if (!node) return;
  const toml::array* array = node->as_array();
  if (!array || !array->is_array_of_tables()) {
    root.fail("spray",
              fmt::format("expected an array of tables [[spray]], got {}", type_name(*node)));
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    const Scope s(*(*array)[i].as_table(), fmt::format("spray[{}]", i), root.source());
    s.allow_only({"name", "position", "direction", "shape", "angle_deg", "fan_axis", "rate",
                  "start", "stop", "droplet_radius", "droplet_speed", "at_wall"});
    SprayConfig c;
    c.name = s.string("name").value_or(fmt::format("spray{}", i));
    const auto position = s.vec3("position");
    if (!position) s.missing("position", "[x, y, z] of the nozzle in the drum frame, m");
    c.position = *position;
    const auto direction = s.vec3("direction");
    if (!direction) s.missing("direction", "[x, y, z] the nozzle points along");
    c.direction = *direction;
    const std::string shape = s.string("shape").value_or("cone");
    if (shape == "flat_fan") {
      c.shape = SprayShape::flat_fan;
      c.fan_axis = s.vec3("fan_axis").value_or(c.fan_axis);
    } else if (shape == "cone") {
      if (s.has("fan_axis")) s.fail("fan_axis", "only with shape = \"flat_fan\"");
    } else {
      s.fail("shape", fmt::format("unknown value '{}' (valid: cone, flat_fan)", shape));
    }
    c.angle_deg = s.number_or("angle_deg", c.angle_deg);
    c.rate = s.required_number("rate", "liquid volume per second, m^3/s");
    c.start = s.number_or("start", c.start);
    c.stop = s.number_or("stop", c.stop);
    c.droplet_radius = s.required_number("droplet_radius", "m, > 0");
    c.droplet_speed = s.required_number("droplet_speed", "speed at the nozzle, m/s");
    const std::string at_wall = s.string("at_wall").value_or("lost");
    if (at_wall == "wet") {
      c.at_wall = SprayAtWall::wet;
    } else if (at_wall != "lost") {
      s.fail("at_wall", fmt::format("unknown value '{}' (valid: lost, wet)", at_wall));
    }
    scene.sprays.push_back(std::move(c));
  }
}

/// A mesh's wall material: [wall]'s, with any of its keys set in the mesh's own table.
MeshMaterial read_mesh_material(const Scope& s, const Material& wall) {
  return {s.number_or("youngs_modulus", wall.youngs_modulus),
          s.number_or("poisson_ratio", wall.poisson_ratio),
          s.number_or("restitution", wall.restitution), s.number_or("friction", wall.friction),
          s.number_or("rolling_friction", wall.rolling_friction)};
}

/// The tables of the array `key` in `wall` ([[wall.KEY]]), each with its path "wall.KEY[i]".
std::vector<Scope> wall_tables(const Scope& wall, std::string_view key) {
  std::vector<Scope> out;
  const toml::node* node = wall.raw().get(key);
  if (!node) return out;
  const toml::array* array = node->as_array();
  if (!array || !array->is_array_of_tables()) {
    wall.fail(
        key, fmt::format("expected an array of tables [[wall.{}]], got {}", key, type_name(*node)));
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    out.emplace_back(*(*array)[i].as_table(), fmt::format("wall.{}[{}]", key, i), wall.source());
  }
  return out;
}

/// [[wall.mesh]]: the STL path relative to the scene file's folder (read by engine/mesh when the
/// scene is checked); the validation checks the numbers.
void read_wall_meshes(const Scope& wall, SceneConfig& scene) {
  for (const Scope& s : wall_tables(wall, "mesh")) {
    s.allow_only({"file", "scale", "offset", "rotation_deg", "attach", "smooth_angle_deg", "closed",
                  "youngs_modulus", "poisson_ratio", "restitution", "friction",
                  "rolling_friction"});
    MeshWallConfig c;
    const auto file = s.string("file");
    if (!file) s.missing("file", "an STL file (binary or ASCII), relative to the scene");
    if (file->empty()) s.fail("file", "must not be empty");
    std::filesystem::path path(*file);
    if (path.is_relative()) path = std::filesystem::path(scene.source).parent_path() / path;
    c.file = path;
    c.scale = s.number_or("scale", c.scale);
    c.offset = s.vec3("offset").value_or(c.offset);
    c.rotation_deg = s.vec3("rotation_deg").value_or(c.rotation_deg);
    const std::string attach = s.string("attach").value_or("drum");
    if (attach == "lab") {
      c.attach = MeshAttach::lab;
    } else if (attach != "drum") {
      s.fail("attach", fmt::format("unknown value '{}' (valid: drum, lab)", attach));
    }
    c.smooth_angle_deg = s.number_or("smooth_angle_deg", c.smooth_angle_deg);
    if (const toml::node* closed = s.raw().get("closed")) {
      if (!closed->as_boolean()) s.fail("closed", "expected true or false");
      c.closed = closed->as_boolean()->get();
    }
    c.material = read_mesh_material(s, scene.wall);
    scene.meshes.push_back(std::move(c));
  }
}

/// [[wall.lifters]]: generated flights; the validation checks the numbers.
void read_wall_lifters(const Scope& wall, SceneConfig& scene) {
  for (const Scope& s : wall_tables(wall, "lifters")) {
    s.allow_only({"count", "height", "length", "thickness", "shape", "angle_deg", "tip",
                  "phase_deg", "youngs_modulus", "poisson_ratio", "restitution", "friction",
                  "rolling_friction"});
    LifterWallConfig c;
    const std::int64_t count = s.integer("count").value_or(c.count);
    if (count < 1 || count > 1000) {
      s.fail("count", fmt::format("must be in [1, 1000], got {}", count));
    }
    c.count = static_cast<int>(count);
    c.height = s.required_number("height", "the flights' radial height, m");
    c.length = s.number_or("length", c.length);
    c.thickness = s.number_or("thickness", c.thickness);
    const std::string shape = s.string("shape").value_or("straight");
    if (shape == "angled") {
      c.shape = LifterKind::angled;
    } else if (shape == "straight") {
      for (const std::string_view key : {"angle_deg", "tip"}) {
        if (s.has(key)) s.fail(key, "only with shape = \"angled\"");
      }
    } else {
      s.fail("shape", fmt::format("unknown value '{}' (valid: straight, angled)", shape));
    }
    c.angle_deg = s.number_or("angle_deg", c.angle_deg);
    c.tip = s.number_or("tip", c.tip);
    c.phase_deg = s.number_or("phase_deg", c.phase_deg);
    c.material = read_mesh_material(s, scene.wall);
    scene.lifters.push_back(std::move(c));
  }
}

void read_performance(const Scope& root, SceneConfig& scene) {
  const auto s = root.table("performance");
  if (!s) return;
  s->allow_only({"verlet_skin", "sort_every", "pair_block_rows"});
  PerformanceConfig& p = scene.performance;
  p.verlet_skin = s->number_or("verlet_skin", p.verlet_skin);
  const std::int64_t every =
      s->integer("sort_every").value_or(static_cast<std::int64_t>(p.sort_every));
  if (every < 0) s->fail("sort_every", fmt::format("must be >= 0 (0: never), got {}", every));
  p.sort_every = static_cast<std::uint64_t>(every);
  const std::int64_t rows =
      s->integer("pair_block_rows").value_or(static_cast<std::int64_t>(p.pair_block_rows));
  if (rows < kMinPairBlockRows || rows > kMaxPairBlockRows) {
    s->fail("pair_block_rows",
            fmt::format("must be in [{}, {}], got {}", kMinPairBlockRows, kMaxPairBlockRows, rows));
  }
  p.pair_block_rows = static_cast<std::uint64_t>(rows);
}

void read_top_level(const Scope& root, SceneConfig& scene) {
  root.allow_only({"name", "description", "gravity", "search", "drum", "particles", "material",
                   "wall", "contact", "liquid", "cohesion", "spray", "fill", "time", "performance",
                   "output"});
  const std::string stem = std::filesystem::path(scene.source).stem().string();
  scene.name = root.string("name").value_or(stem.empty() ? "scene" : stem);
  scene.description = root.string("description").value_or("");
  scene.gravity = root.vec3("gravity").value_or(scene.gravity);
  scene.search_method = root.string("search").value_or(scene.search_method);
}

/// The node of a dotted key ("drum.diameter", "particles[1].radius") in the file, or the deepest
/// table on its path that exists (a key left at its default has no node of its own).
const toml::node* node_of(const toml::table& root, std::string_view key) {
  const toml::node* node = &root;
  while (!key.empty() && node) {
    const std::size_t dot = key.find('.');
    std::string_view part = key.substr(0, dot);
    key = dot == std::string_view::npos ? std::string_view() : key.substr(dot + 1);
    std::optional<std::size_t> index;
    if (const std::size_t open = part.find('['); open != std::string_view::npos) {
      index = std::stoul(std::string(part.substr(open + 1)));
      part = part.substr(0, open);
    }
    const toml::table* table = node->as_table();
    const toml::node* next = table ? table->get(part) : nullptr;
    if (next && index) {
      const toml::array* array = next->as_array();
      next = array && *index < array->size() ? array->get(*index) : nullptr;
    }
    if (!next) return node == &root ? nullptr : node;
    node = next;
  }
  return node;
}

/// Throws the validation's problem as "<file>: <key>: <reason> (line N)".
[[noreturn]] void fail_at(const toml::table& root, const std::string& source,
                          const SceneProblem& problem) {
  const toml::node* node = node_of(root, problem.key);
  const auto line = node ? node->source().begin.line : 0;
  if (line > 0) {
    throw InputError(
        fmt::format("{}: {}: {} (line {})", source, problem.key, problem.reason, line));
  }
  throw InputError(fmt::format("{}: {}: {}", source, problem.key, problem.reason));
}

SceneConfig build_scene(const toml::table& table, std::string_view source) {
  SceneConfig scene;
  scene.source = std::string(source);
  const Scope root(table, "", scene.source);
  read_top_level(root, scene);
  read_particles(root, scene);
  read_drum(root, scene);
  const Scope material = root.required_table("material");
  material.allow_only({"density", "youngs_modulus", "poisson_ratio", "restitution", "friction",
                       "rolling_friction"});
  scene.material = read_material(material, Material{}, false);
  scene.wall = scene.material;
  if (const auto wall = root.table("wall")) {
    wall->allow_only({"youngs_modulus", "poisson_ratio", "restitution", "friction",
                      "rolling_friction", "mesh", "lifters"});
    scene.wall = read_material(*wall, scene.material, true);
    read_wall_meshes(*wall, scene);
    read_wall_lifters(*wall, scene);
  }
  read_contact(root, scene);
  read_liquid(root, scene);
  read_cohesion(root, scene);
  read_sprays(root, scene);
  read_fill(root, scene);
  read_time(root, scene);
  read_performance(root, scene);
  read_output(root, scene);
  if (const auto problem = scene_problem(scene)) fail_at(table, scene.source, *problem);
  if (scene.has_meshes()) {  // the files: read now, so a bad one stops the scene at loading
    try {
      build_wall_meshes(scene);
    } catch (const MeshWallError& e) {
      fail_at(table, scene.source, SceneProblem{e.key(), e.reason()});
    }
  }
  return scene;
}

}  // namespace

SceneConfig parse_scene(std::string_view toml_text, std::string_view source) {
  toml::table table;
  try {
    table = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    std::string reason(e.description());
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(fmt::format("{}: line {}, column {}: TOML syntax error: {}", source, b.line,
                                 b.column, reason));
  }
  return build_scene(table, source);
}

SceneConfig load_scene(const std::filesystem::path& file) {
  const std::string source = file.string();
  std::ifstream in(file, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(file, ec)) {
    throw InputError(fmt::format("{}: cannot read scene file", source));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: cannot read scene file", source));
  return parse_scene(text.str(), source);
}

}  // namespace drumlab
