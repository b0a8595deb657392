// drumlab law SCENE [--pair A,B | --wall A] --out DIR: a contact law of the scene seen on two
// bodies (engine/contact/law_probe.hpp): law.csv and law.png in DIR.
#include <cmath>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "engine/contact/law_probe.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/scene/scene_config.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/law_chart.hpp"
#endif

namespace drumlab::cli {
namespace {

struct LawOptions {
  std::string scene;
  std::vector<std::string> pair;  ///< two classes, or none
  std::string wall;
  std::string out;
  double overlap = -1.0;
  std::size_t steps = 400;
};

// A class by name or by index.
std::uint8_t class_index(const SceneConfig& scene, const std::string& name) {
  for (std::size_t c = 0; c < scene.classes.size(); ++c) {
    if (scene.classes[c].name == name || std::to_string(c) == name) {
      return static_cast<std::uint8_t>(c);
    }
  }
  std::string names;
  for (const ParticleClass& c : scene.classes) names += (names.empty() ? "" : ", ") + c.name;
  throw InputError(
      fmt::format("{}: no particle class '{}' (classes: {})", scene.source, name, names));
}

void run_law(const LawOptions& o) {
  const SceneConfig scene = load_scene(o.scene);
  LawProbeOptions probe;
  probe.overlap = o.overlap;
  probe.steps = o.steps;
  if (!o.pair.empty() && !o.wall.empty()) throw InputError("law: give --pair or --wall, not both");
  if (!o.wall.empty()) {
    probe.wall = true;
    probe.class_a = class_index(scene, o.wall);
  } else if (!o.pair.empty()) {
    probe.class_a = class_index(scene, o.pair[0]);
    probe.class_b = class_index(scene, o.pair[1]);
  }
  const LawCurve curve = probe_law(scene, probe);
  const std::filesystem::path dir(o.out);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("{}: cannot create the directory: {}", o.out, ec.message()));
  write_file_atomically(dir / "law.csv", [&](std::ostream& out) {
    out << "gap_or_overlap_m,normal_force_N,bridge_volume_m3,branch\n";
    for (const LawSample& s : curve.samples) {
      out << fmt::format("{:.17g},{:.17g},{:.17g},{}\n", s.gap, s.normal_force, s.bridge_volume,
                         s.retreat ? "retreat" : "approach");
    }
  });
  double pull = 0.0;
  for (const LawSample& s : curve.samples) pull = std::min(pull, s.normal_force);
  fmt::print("law               {} ({} samples per branch, gap < 0: overlap)\n", curve.label,
             o.steps);
  fmt::print("largest pull      {:.4g} N\n", -pull);
  if (std::isfinite(curve.rupture_gap)) {
    fmt::print("rupture           between s = {:.6g} and {:.6g} m (s_rup = {:.6g} m)\n",
               curve.last_bridged_gap, curve.rupture_gap, curve.predicted_rupture);
  } else {
    fmt::print("rupture           no bridge formed\n");
  }
  fmt::print("wrote             {}\n", (dir / "law.csv").string());
#ifdef DRUMLAB_WITH_RENDER
  render::write_law_chart(curve, dir / "law.png");
  fmt::print("wrote             {}\n", (dir / "law.png").string());
#endif
}

}  // namespace

void add_law_command(CLI::App& app) {
  auto o = std::make_shared<LawOptions>();
  CLI::App* cmd = app.add_subcommand(
      "law",
      "A contact law of the scene on two bodies: approach, overlap, pull apart past rupture");
  cmd->add_option("scene", o->scene, "scene file (TOML)")->required();
  cmd->add_option("--pair", o->pair, "two particle classes A,B (names or indices; default 0,0)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--wall", o->wall, "one class against the drum mantle");
  cmd->add_option("--overlap", o->overlap,
                  "deepest overlap, m (default: 2 % of the smaller radius)");
  cmd->add_option("--steps", o->steps, "positions per branch (default 400)")
      ->check(CLI::Range(2, 1000000));
  cmd->add_option("--out", o->out, "output directory (law.csv, law.png)")->required();
  cmd->callback([o] { run_law(*o); });
}

}  // namespace drumlab::cli
