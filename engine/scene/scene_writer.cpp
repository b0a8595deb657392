// SceneConfig -> TOML text, in the order of the shipped scenes. Numbers go through fmt's shortest
// round-trip format ("{}"): toml++ 3.3 built with GCC prints doubles with 17 significant digits
// (TOML_FLOAT_CHARCONV is off), exact but unreadable (0.1 -> 0.10000000000000001). toml++ quotes
// the strings; tests/unit/test_scene_writer.cpp parses every written scene back.
#include "engine/scene/scene_writer.hpp"

#include <cstdint>
#include <limits>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "engine/io/atomic_file.hpp"
#include "engine/types.hpp"

namespace drumlab {
namespace {

namespace fs = std::filesystem;

/// A double as a TOML float that parses back to the same bits.
std::string number(double v) {
  std::string text = fmt::format("{}", v);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";  // "n": inf, nan
  return text;
}

/// A TOML basic string ("...", escapes as needed; UTF-8 kept), as in the shipped scenes.
std::string string(std::string_view s) {
  std::ostringstream out;
  const toml::value<std::string> value{std::string(s)};
  out << toml::toml_formatter(value, toml::format_flags::allow_unicode_strings);
  return out.str();
}

std::string vec3(const Vec3& v) {
  return fmt::format("[{}, {}, {}]", number(v.x()), number(v.y()), number(v.z()));
}

/// A TOML integer (int64); throws for values the loader could not read back.
std::string integer(std::uint64_t v, std::string_view key) {
  if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    throw InputError(fmt::format("{}: {} does not fit a TOML integer", key, v));
  }
  return fmt::format("{}", v);
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

class Writer {
 public:
  void line(std::string_view key, const std::string& value) {
    out_ += fmt::format("{} = {}\n", key, value);
  }
  void table(std::string_view header) { out_ += fmt::format("\n{}\n", header); }
  void append(const std::string& text) { out_ += text; }
  std::string text() && { return std::move(out_); }

 private:
  std::string out_;
};

void write_top_level(Writer& w, const SceneConfig& s) {
  w.line("name", string(s.name));
  w.line("description", string(s.description));
  w.line("gravity", vec3(s.gravity));
  w.line("search", string(s.search_method));
}

void write_drum(Writer& w, const DrumConfig& d) {
  w.table("[drum]");
  w.line("diameter", number(d.diameter));
  w.line("depth", number(d.depth));
  w.line("omega", number(d.omega));
  w.line("tilt_deg", number(tilt_in_degrees(d.tilt)));
  w.line("ends", string(d.ends == DrumEnds::periodic ? "periodic" : "caps"));
}

void write_particles(Writer& w, const std::vector<ParticleClass>& classes) {
  for (const ParticleClass& c : classes) {
    w.table("[[particles]]");
    w.line("name", string(c.name));
    w.line("radius", number(c.radius));
    w.line("volume_fraction", number(c.volume_fraction));
  }
}

void write_materials(Writer& w, const Material& m, const Material& wall) {
  w.table("[material]");
  w.line("density", number(m.density));
  w.line("youngs_modulus", number(m.youngs_modulus));
  w.line("poisson_ratio", number(m.poisson_ratio));
  w.line("restitution", number(m.restitution));
  w.line("friction", number(m.friction));
  w.line("rolling_friction", number(m.rolling_friction));

  Writer keys;  // the [wall] keys that differ from [material] (each defaults to it)
  auto differing = [&](std::string_view key, double value, double material_value) {
    if (value != material_value) keys.line(key, number(value));
  };
  differing("youngs_modulus", wall.youngs_modulus, m.youngs_modulus);
  differing("poisson_ratio", wall.poisson_ratio, m.poisson_ratio);
  differing("restitution", wall.restitution, m.restitution);
  differing("friction", wall.friction, m.friction);
  differing("rolling_friction", wall.rolling_friction, m.rolling_friction);
  const std::string wall_keys = std::move(keys).text();
  if (!wall_keys.empty()) {
    w.table("[wall]");
    w.append(wall_keys);
  }
}

void write_contact(Writer& w, const ContactConfig& c) {
  w.table("[contact]");
  if (c.normal == NormalLaw::linear) {
    w.line("normal", string("linear"));
    w.line("linear_stiffness", number(c.linear_stiffness));
  } else {
    w.line("normal", string("hertz"));
  }
}

void write_liquid(Writer& w, const LiquidConfig& l) {
  if (!l.enabled) return;
  w.table("[liquid]");
  w.line("surface_tension", number(l.surface_tension));
  w.line("contact_angle_deg", number(l.contact_angle_deg));
  w.line("bridge_volume", number(l.bridge_volume));
}

void write_fill(Writer& w, const FillConfig& f, const fs::path& folder) {
  w.table("[fill]");
  switch (f.kind) {
    case FillKind::random:
      w.line("kind", string("random"));
      w.line("count", integer(f.count, "fill.count"));
      w.line("volume_fraction", number(f.volume_fraction));
      w.line("seed", integer(f.seed, "fill.seed"));
      w.line("settle_time", number(f.settle_time));
      break;
    case FillKind::file:
      w.line("kind", string("file"));
      w.line("file", string(relative_path(f.file, folder).generic_string()));
      w.line("settle_time", number(f.settle_time));
      break;
    case FillKind::paper_packing:
      w.line("kind", string("paper_packing"));
      w.line("box", vec3(f.box));
      break;
  }
}

void write_time(Writer& w, const TimeConfig& t) {
  w.table("[time]");
  if (t.dt) {
    w.line("dt", number(*t.dt));
  } else {
    w.line("dt_factor", number(t.dt_factor));
  }
  if (t.duration) w.line("duration", number(*t.duration));
  if (t.revolutions) w.line("revolutions", number(*t.revolutions));
}

void write_performance(Writer& w, const PerformanceConfig& p) {
  w.table("[performance]");
  w.line("verlet_skin", number(p.verlet_skin));
  w.line("sort_every", integer(p.sort_every, "performance.sort_every"));
}

void write_output(Writer& w, const SceneConfig& s) {
  w.table("[output]");
  if (s.output.directory != default_output_directory(s.name)) {
    w.line("directory", string(s.output.directory));
  }
  w.line("diagnostics_every", integer(s.output.diagnostics_every, "output.diagnostics_every"));
}

}  // namespace

std::string scene_to_toml(const SceneConfig& scene, const fs::path& folder) {
  Writer w;
  w.append("# Written by drumlab (engine/scene/scene_writer.cpp); keys: scenes/README.md.\n\n");
  write_top_level(w, scene);
  write_drum(w, scene.drum);
  write_particles(w, scene.classes);
  write_materials(w, scene.material, scene.wall);
  write_contact(w, scene.contact);
  write_liquid(w, scene.liquid);
  write_fill(w, scene.fill, folder);
  write_time(w, scene.time);
  write_performance(w, scene.performance);
  write_output(w, scene);
  return std::move(w).text();
}

std::string scene_to_toml(const SceneConfig& scene) {
  return scene_to_toml(scene, fs::path(scene.source).parent_path());
}

void save_scene(const SceneConfig& scene, const fs::path& file) {
  std::string text;
  try {
    text = scene_to_toml(scene, file.parent_path());
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", file.string(), e.what()));
  }
  write_file_atomically(file, [&](std::ostream& out) { out << text; });
}

}  // namespace drumlab
