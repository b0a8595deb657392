#include "app/cli/sweep_plan.hpp"

#include <charconv>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "engine/analysis/agglomerates.hpp"
#include "engine/drum_orbit.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/scene/scene_keys.hpp"
#include "engine/scene/scene_writer.hpp"

namespace drumlab::cli {
namespace {

std::string run_name(std::size_t index, const std::vector<SweepSet>& sets,
                     const std::vector<std::string>& values, std::int64_t seed) {
  std::string name = fmt::format("r{:03d}", index);
  for (std::size_t k = 0; k < sets.size(); ++k) name += "_" + sets[k].key + "=" + values[k];
  if (seed >= 0) name += fmt::format("_seed={}", seed);
  for (char& c : name) {
    if (c == '/' || c == ' ') c = '_';
  }
  return name;
}

}  // namespace

SweepSet parse_sweep_set(const std::string& spec) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size()) {
    throw InputError(
        fmt::format("--set '{}': not KEY=V1,V2,... (a dotted scene key such as "
                    "liquid.surface_tension)",
                    spec));
  }
  SweepSet s{spec.substr(0, eq), split_text(spec.substr(eq + 1), ',')};
  for (const std::string& v : s.values) {
    if (v.empty()) throw InputError(fmt::format("--set '{}': an empty value", spec));
  }
  return s;
}

std::vector<SweepRun> plan_sweep(const std::filesystem::path& scene,
                                 const std::vector<SweepSet>& sets,
                                 const std::vector<std::int64_t>& seeds) {
  toml::table base;
  try {
    base = toml::parse_file(scene.string());
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}: {}", scene.string(), e.description()));
  }
  if (auto* file = base["fill"]["file"].as_string()) {  // the runs' scenes live elsewhere
    const std::filesystem::path csv = file->get();
    if (csv.is_relative()) *file = std::filesystem::absolute(scene.parent_path() / csv).string();
  }
  std::vector<std::vector<std::string>> combos{{}};
  for (const SweepSet& s : sets) {
    std::vector<std::vector<std::string>> next;
    for (const auto& c : combos) {
      for (const std::string& v : s.values) {
        next.push_back(c);
        next.back().push_back(v);
      }
    }
    combos = std::move(next);
  }
  const std::vector<std::int64_t> seed_list = seeds.empty() ? std::vector<std::int64_t>{-1} : seeds;
  std::vector<SweepRun> runs;
  for (const auto& values : combos) {
    for (const std::int64_t seed : seed_list) {
      toml::table t = base;
      std::string label = scene.string();
      for (std::size_t k = 0; k < sets.size(); ++k) {
        const std::string set = sets[k].key + "=" + values[k];
        set_scene_key(t, sets[k].key, values[k], "--set " + set);
        label += " --set " + set;
      }
      if (seed >= 0) set_scene_key(t, "fill.seed", std::to_string(seed), "--set (--seeds)");
      std::ostringstream text;
      text << t << '\n';
      SweepRun run{run_name(runs.size(), sets, values, seed), values, seed,
                   with_shortest_floats(text.str()), false};
      try {
        const SceneConfig config = parse_scene(run.scene_text, label);
        run.has_bonds = scene_has_bonds(config);
        if (const DrumOrbit& o = config.drum.orbit; o.active()) {
          const double r = 0.5 * config.drum.diameter;
          run.critical_ratios = {critical_speed_ratio(o, r - config.max_radius()),
                                 critical_speed_ratio(o, r - config.min_radius())};
        }
      } catch (const InputError& e) {
        throw InputError(fmt::format("--set: {}", e.what()));
      }
      runs.push_back(std::move(run));
    }
  }
  return runs;
}

}  // namespace drumlab::cli
