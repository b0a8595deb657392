#pragma once
// Shared by `drumlab bench throughput` and `drumlab bench search`: the rolling state of a scene
// (fill, settle with the drum at rest, turn a little), cached as a checkpoint so every method and
// every later bench run starts from the same particles; plus memory probes and the output folder.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "engine/scene/scene_config.hpp"
#include "engine/simulation_state.hpp"

namespace drumlab {
class Simulation;
}

namespace drumlab::bench {

struct RollingPlan {
  double settle_time = -1.0;      ///< s with the drum at rest; < 0: the scene's fill.settle_time
  double turn_revolutions = 0.1;  ///< drum turns after settling (the demo's 0.1: surface flowing)
  bool fresh = false;             ///< ignore a cached state
  std::filesystem::path cache_dir = "out/bench";
};

struct RollingState {
  SceneConfig scene;
  SimulationState state;
  std::string origin;  ///< one line: where the state came from (cache file, or how it was made)
};

/// Loads the scene and returns its rolling state (search "auto" resolved on it and printed as
/// `drumlab run` prints it): from CACHE/<scene>_rolling.h5 when that exists
/// and was made from the same scene text with the same plan, otherwise made now (and cached when
/// any step was simulated). Throws InputError for a bad scene or an unusable cache folder.
RollingState rolling_state(const std::string& scene_file, const RollingPlan& plan);

/// The untimed steps before a timed window: `steps` steps, then, if the scene re-orders its
/// particles (performance.sort_every > 0), one re-ordering, so that the window does not pay the
/// run's first one: the first touch of its scratch buffers (page faults), ~3x a later one. A long
/// run pays that once; LAMMPS's loop time leaves its setup out the same way.
void warm_up(Simulation& sim, std::uint64_t steps);

/// Bytes the allocator holds for live objects now: engine/memory_probe.hpp's probe.
std::size_t heap_bytes_in_use();
/// Peak resident set size of the process so far (getrusage ru_maxrss), bytes.
std::size_t peak_rss_bytes();

/// Creates `dir` (and parents) or throws InputError naming it.
void make_output_dir(const std::filesystem::path& dir);

}  // namespace drumlab::bench
