#pragma once
// The runs of `drumlab sweep`: the scene once per combination of the --set values (and per seed),
// each as the scene's TOML with those keys set, checked by the scene loader before anything runs.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace drumlab::cli {

/// One --set KEY=V1,V2,...: a dotted scene key (`liquid.surface_tension`) and its values.
struct SweepSet {
  std::string key;
  std::vector<std::string> values;
};

/// Parses "KEY=V1,V2,..."; throws InputError naming the --set for a missing key or value.
SweepSet parse_sweep_set(const std::string& spec);

struct SweepRun {
  std::string name;                 ///< run folder: r003_liquid.surface_tension=0.05_seed=2
  std::vector<std::string> values;  ///< one per set, as given
  std::int64_t seed = -1;           ///< fill.seed set by --seeds; -1: the scene's
  std::string scene_text;           ///< the scene with the values set (TOML)
  bool has_bonds = false;           ///< the scene forms bonds (agglomerates are measured)
  /// A planetary drum: the critical |1 + k| of its largest and smallest particles
  /// (engine/drum_orbit.hpp); empty without [drum.orbit].
  std::vector<double> critical_ratios{};
};

/// Every run, in order: the first set varies slowest, the seeds fastest. Each run's scene is the
/// scene file with the values set (tables created where missing; an existing key keeps its TOML
/// type), [fill] file made absolute, and validated by the scene loader: a bad key or value throws
/// InputError naming the --set and the loader's reason.
std::vector<SweepRun> plan_sweep(const std::filesystem::path& scene,
                                 const std::vector<SweepSet>& sets,
                                 const std::vector<std::int64_t>& seeds);

}  // namespace drumlab::cli
