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

#include "engine/scene/material_check.hpp"
#include "engine/scene/scene_config.hpp"
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

// ---- range checks --------------------------------------------------------------------------

void check_positive(const Scope& s, std::string_view key, double v) {
  if (!(v > 0.0)) s.fail(key, fmt::format("must be > 0, got {}", v));
}

void check_non_negative(const Scope& s, std::string_view key, double v) {
  if (!(v >= 0.0)) s.fail(key, fmt::format("must be >= 0, got {}", v));
}

/// The material ranges of engine/scene/material_check.hpp, reported for the key of this table.
void check_material_value(const Scope& s, std::string_view key, double v) {
  if (const auto reason = material_value_problem(key, v)) s.fail(key, *reason);
}

double positive(const Scope& s, std::string_view key, std::string_view what) {
  const double v = s.required_number(key, what);
  check_positive(s, key, v);
  return v;
}

// ---- sections --------------------------------------------------------------------------------

/// Reads the keys of a material table; `base` supplies values for omitted keys when
/// `all_optional` (the [wall] table), otherwise the core keys are required.
Material read_material(const Scope& s, const Material& base, bool all_optional) {
  Material m = base;
  auto get = [&](std::string_view key, double fallback, std::string_view what) {
    if (all_optional) return s.number_or(key, fallback);
    return s.required_number(key, what);
  };
  if (!all_optional) {
    m.density = get("density", m.density, "kg/m^3");
    check_material_value(s, "density", m.density);
  }
  m.youngs_modulus = get("youngs_modulus", m.youngs_modulus, "Young's modulus E, Pa");
  check_material_value(s, "youngs_modulus", m.youngs_modulus);
  m.poisson_ratio = get("poisson_ratio", m.poisson_ratio, "Poisson ratio nu");
  check_material_value(s, "poisson_ratio", m.poisson_ratio);
  m.restitution = get("restitution", m.restitution, "coefficient of restitution e");
  check_material_value(s, "restitution", m.restitution);
  m.friction = get("friction", m.friction, "sliding friction coefficient mu");
  check_material_value(s, "friction", m.friction);
  m.rolling_friction = s.number_or("rolling_friction", all_optional ? m.rolling_friction : 0.0);
  check_material_value(s, "rolling_friction", m.rolling_friction);
  return m;
}

void read_particles(const Scope& root, SceneConfig& scene) {
  const toml::node* node = root.raw().get("particles");
  if (!node) root.missing("particles", "one [[particles]] table per size class");
  const toml::array* array = node->as_array();
  if (!array || !array->is_array_of_tables()) {
    root.fail("particles",
              fmt::format("expected an array of tables [[particles]], got {}", type_name(*node)));
  }
  if (array->empty()) root.fail("particles", "needs at least one [[particles]] class");
  if (array->size() > 256) root.fail("particles", "at most 256 size classes are supported");
  std::set<std::string> names;
  double sum = 0.0;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const Scope s(*(*array)[i].as_table(), fmt::format("particles[{}]", i), root.source());
    s.allow_only({"name", "radius", "volume_fraction"});
    ParticleClass c;
    c.name = s.string("name").value_or(fmt::format("class{}", i));
    if (c.name.empty()) s.fail("name", "must not be empty");
    if (!names.insert(c.name).second) s.fail("name", fmt::format("duplicate class '{}'", c.name));
    c.radius = positive(s, "radius", "particle radius, m");
    if (array->size() == 1) {
      c.volume_fraction = s.number_or("volume_fraction", 1.0);
    } else {
      c.volume_fraction = s.required_number("volume_fraction", "share of the solid volume");
    }
    if (!(c.volume_fraction > 0.0 && c.volume_fraction <= 1.0)) {
      s.fail("volume_fraction", fmt::format("must be in (0, 1], got {}", c.volume_fraction));
    }
    sum += c.volume_fraction;
    scene.classes.push_back(c);
  }
  if (std::abs(sum - 1.0) > 1e-6) {
    root.fail("particles", fmt::format("volume_fraction values sum to {}, must sum to 1", sum));
  }
}

void read_drum(const Scope& root, SceneConfig& scene) {
  const Scope s = root.required_table("drum");
  s.allow_only({"diameter", "depth", "omega", "rpm", "tilt_deg", "ends"});
  DrumConfig& d = scene.drum;
  const double rmax = scene.max_radius();
  d.diameter = positive(s, "diameter", "drum diameter D, m");
  if (!(d.diameter > 2.0 * rmax)) {
    s.fail("diameter", fmt::format("must exceed 2 * largest particle radius = {}", 2.0 * rmax));
  }
  d.depth = positive(s, "depth", "drum depth H along the axis, m");
  if (!(d.depth > 2.0 * rmax)) {
    s.fail("depth", fmt::format("must exceed 2 * largest particle radius = {}", 2.0 * rmax));
  }
  const auto omega = s.number("omega");
  const auto rpm = s.number("rpm");
  if (omega && rpm) s.fail("rpm", "give either omega (rad/s) or rpm, not both");
  if (!omega && !rpm) s.missing("omega", "drum angular velocity: omega in rad/s or rpm");
  d.omega = omega ? *omega : *rpm * 2.0 * std::numbers::pi / 60.0;
  const double tilt_deg = s.number_or("tilt_deg", 0.0);
  if (!(tilt_deg >= 0.0 && tilt_deg < 90.0)) {
    s.fail("tilt_deg", fmt::format("must be in [0, 90) degrees, got {}", tilt_deg));
  }
  d.tilt = tilt_from_degrees(tilt_deg);
  const std::string ends = s.string("ends").value_or("caps");
  if (ends == "caps") {
    d.ends = DrumEnds::caps;
  } else if (ends == "periodic") {
    d.ends = DrumEnds::periodic;
  } else {
    s.fail("ends", fmt::format("unknown value '{}' (valid: caps, periodic)", ends));
  }
}

void read_contact(const Scope& root, SceneConfig& scene) {
  const auto s = root.table("contact");
  if (!s) return;
  s->allow_only({"normal", "linear_stiffness"});
  const std::string normal = s->string("normal").value_or("hertz");
  if (normal == "hertz") {
    scene.contact.normal = NormalLaw::hertz;
    if (s->has("linear_stiffness")) {
      s->fail("linear_stiffness", "only used with normal = \"linear\"");
    }
  } else if (normal == "linear") {
    scene.contact.normal = NormalLaw::linear;
    scene.contact.linear_stiffness =
        positive(*s, "linear_stiffness", "normal spring stiffness of the linear law, N/m");
  } else {
    s->fail("normal", fmt::format("unknown value '{}' (valid: hertz, linear)", normal));
  }
}

void read_random_fill(const Scope& s, FillConfig& f) {
  s.allow_only({"kind", "count", "volume_fraction", "seed", "settle_time"});
  const auto count = s.integer("count");
  if (!count) s.missing("count", "total number of particles");
  if (*count <= 0) s.fail("count", fmt::format("must be >= 1, got {}", *count));
  if (*count > 100'000'000) s.fail("count", fmt::format("{} is more than 1e8 particles", *count));
  f.count = static_cast<std::size_t>(*count);
  f.volume_fraction = s.number_or("volume_fraction", f.volume_fraction);
  if (!(f.volume_fraction > 0.0 && f.volume_fraction <= 0.55)) {
    s.fail("volume_fraction",
           fmt::format("must be in (0, 0.55] (loose random packing), got {}", f.volume_fraction));
  }
  const std::int64_t seed = s.integer("seed").value_or(static_cast<std::int64_t>(f.seed));
  if (seed < 0) s.fail("seed", fmt::format("must be >= 0, got {}", seed));
  f.seed = static_cast<std::uint64_t>(seed);
  f.settle_time = s.number_or("settle_time", f.settle_time);
  check_non_negative(s, "settle_time", f.settle_time);
}

void read_paper_fill(const Scope& s, SceneConfig& scene) {
  s.allow_only({"kind", "box"});
  const auto box = s.vec3("box");
  if (!box) s.missing("box", "[x, y, z] size of the packing box, m");
  for (int k = 0; k < 3; ++k) {
    if (!((*box)[k] > 0.0)) s.fail("box", "all three sizes must be > 0");
  }
  scene.fill.box = *box;
  scene.fill.count = 0;
  const auto& c = scene.classes;
  if (c.size() != 3 || !(c[0].radius < c[1].radius && c[1].radius < c[2].radius)) {
    s.fail("kind",
           "\"paper_packing\" needs exactly three [[particles]] classes, small to large radius");
  }
}

/// [fill] kind = "file": the CSV path relative to the scene file's folder. The file itself is read
/// by file_fill (engine/fill/file_fill.hpp); here only that it exists.
void read_file_fill(const Scope& s, SceneConfig& scene) {
  s.allow_only({"kind", "file", "settle_time"});
  const auto file = s.string("file");
  if (!file) s.missing("file", "CSV of the initial particles x,y,z,r[,vx,vy,vz], m and m/s");
  if (file->empty()) s.fail("file", "must not be empty");
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
  check_non_negative(s, "settle_time", scene.fill.settle_time);
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
  s->allow_only({"dt", "dt_factor", "duration", "revolutions"});
  TimeConfig& t = scene.time;
  if (s->has("dt") && s->has("dt_factor")) s->fail("dt_factor", "give either dt or dt_factor");
  if (auto dt = s->number("dt")) {
    check_positive(*s, "dt", *dt);
    t.dt = *dt;
  }
  t.dt_factor = s->number_or("dt_factor", t.dt_factor);
  if (!(t.dt_factor > 0.0 && t.dt_factor <= 1.0)) {
    s->fail("dt_factor",
            fmt::format("must be in (0, 1] (fraction of the Rayleigh time), got {}", t.dt_factor));
  }
  if (s->has("duration") && s->has("revolutions")) {
    s->fail("revolutions", "give either duration or revolutions, not both");
  }
  if (auto d = s->number("duration")) {
    check_positive(*s, "duration", *d);
    t.duration = *d;
  }
  if (auto r = s->number("revolutions")) {
    check_positive(*s, "revolutions", *r);
    if (scene.drum.omega == 0.0) s->fail("revolutions", "needs a turning drum (omega != 0)");
    t.revolutions = *r;
  }
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
  if (scene.output.directory.empty()) s->fail("directory", "must not be empty");
  const std::int64_t every = s->integer("diagnostics_every").value_or(1000);
  if (every < 1) s->fail("diagnostics_every", fmt::format("must be >= 1, got {}", every));
  scene.output.diagnostics_every = static_cast<std::uint64_t>(every);
}

void read_liquid(const Scope& root, SceneConfig& scene) {
  const auto s = root.table("liquid");
  if (!s) return;
  s->allow_only({"surface_tension", "contact_angle_deg", "bridge_volume"});
  LiquidConfig& l = scene.liquid;
  l.enabled = true;
  l.surface_tension = s->required_number("surface_tension", "N/m, > 0");
  if (!(l.surface_tension > 0.0)) {
    s->fail("surface_tension", fmt::format("must be > 0 (N/m), got {}", l.surface_tension));
  }
  l.contact_angle_deg = s->number_or("contact_angle_deg", 0.0);
  if (!(l.contact_angle_deg >= 0.0 && l.contact_angle_deg < 90.0)) {
    s->fail("contact_angle_deg",
            fmt::format("must be in [0, 90) degrees, got {}", l.contact_angle_deg));
  }
  l.bridge_volume = s->required_number("bridge_volume", "m^3, > 0");
  if (!(l.bridge_volume > 0.0)) {
    s->fail("bridge_volume", fmt::format("must be > 0 (m^3), got {}", l.bridge_volume));
  }
}

void read_performance(const Scope& root, SceneConfig& scene) {
  const auto s = root.table("performance");
  if (!s) return;
  s->allow_only({"verlet_skin", "sort_every"});
  PerformanceConfig& p = scene.performance;
  p.verlet_skin = s->number_or("verlet_skin", p.verlet_skin);
  if (!(p.verlet_skin > 0.0 && p.verlet_skin <= 10.0)) {
    s->fail("verlet_skin", fmt::format("must be in (0, 10] (units of the smallest radius), got {}",
                                       p.verlet_skin));
  }
  const std::int64_t every =
      s->integer("sort_every").value_or(static_cast<std::int64_t>(p.sort_every));
  if (every < 0) s->fail("sort_every", fmt::format("must be >= 0 (0: never), got {}", every));
  p.sort_every = static_cast<std::uint64_t>(every);
}

void read_top_level(const Scope& root, SceneConfig& scene) {
  root.allow_only({"name", "description", "gravity", "search", "drum", "particles", "material",
                   "wall", "contact", "liquid", "fill", "time", "performance", "output"});
  const std::string stem = std::filesystem::path(scene.source).stem().string();
  scene.name = root.string("name").value_or(stem.empty() ? "scene" : stem);
  if (scene.name.empty()) root.fail("name", "must not be empty");
  scene.description = root.string("description").value_or("");
  scene.gravity = root.vec3("gravity").value_or(scene.gravity);
  scene.search_method = root.string("search").value_or(scene.search_method);
  if (scene.search_method.empty()) root.fail("search", "must not be empty");
  if (scene.search_method != "auto") {
    try {
      make_search(scene.search_method);
    } catch (const InputError& e) {
      root.fail("search", e.what());
    }
  }
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
    wall->allow_only(
        {"youngs_modulus", "poisson_ratio", "restitution", "friction", "rolling_friction"});
    scene.wall = read_material(*wall, scene.material, true);
  }
  read_contact(root, scene);
  read_liquid(root, scene);
  read_fill(root, scene);
  read_time(root, scene);
  read_performance(root, scene);
  read_output(root, scene);
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
