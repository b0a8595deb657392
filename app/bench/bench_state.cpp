#include "app/bench/bench_state.hpp"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "app/cli/run_session.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/memory_probe.hpp"
#include "engine/session/run_session.hpp"
#include "engine/simulation.hpp"

namespace drumlab::bench {

namespace {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// What the cached state depends on: the scene text, a file fill's packing and the plan.
std::string cache_key(const std::string& scene_file, const SceneConfig& scene, double settle_time,
                      double revolutions) {
  const auto hash = [](const std::string& text) { return std::hash<std::string>{}(text); };
  std::string key = fmt::format("scene-text-hash {:016x} settle {:.17g} turn {:.17g}\n",
                                hash(read_text(scene_file)), settle_time, revolutions);
  if (scene.fill.kind == FillKind::file)
    key += fmt::format("fill-file-hash {:016x}\n", hash(read_text(scene.fill.file)));
  return key;
}

/// Fill (the scene's [fill] kind), settle with the drum at rest, turn: the state to benchmark.
/// `scene` comes back with search "auto" resolved.
SimulationState make_rolling(SceneConfig& scene, double settle_time, double revolutions) {
  const auto t0 = std::chrono::steady_clock::now();
  SessionOptions options;
  options.settle_time = settle_time;
  RunSession session(scene, options);
  const double fill_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (session.auto_choice()) cli::print_auto_choice(*session.auto_choice());
  scene = session.scene();
  const Simulation& sim = session.simulation();
  const std::uint64_t settle = session.settle_steps();
  const double omega = std::abs(scene.drum.omega);
  const auto turn = omega > 0.0 ? static_cast<std::uint64_t>(std::ceil(
                                      revolutions * 2.0 * std::numbers::pi / omega / sim.dt()))
                                : 0;
  fmt::print("prepare           {} particles filled in {:.2f} s; settle {} steps, turn {} steps\n",
             sim.particles().size(), fill_seconds, settle, turn);
  session.settle();
  session.advance(turn);
  return sim.state();
}

}  // namespace

RollingState rolling_state(const std::string& scene_file, const RollingPlan& plan) {
  RollingState r;
  r.scene = load_dynamic_scene(scene_file);
  const double settle = plan.settle_time >= 0.0 ? plan.settle_time : r.scene.fill.settle_time;
  const std::string key = cache_key(scene_file, r.scene, settle, plan.turn_revolutions);
  const auto file = plan.cache_dir / (r.scene.name + "_rolling.h5");
  const auto key_file = plan.cache_dir / (r.scene.name + "_rolling.key");
  if (!plan.fresh && std::filesystem::exists(file) && read_text(key_file) == key) {
    Checkpoint c = read_checkpoint(file);
    // A random fill names its count; a file fill's packing is in the key.
    const bool count_ok =
        r.scene.fill.kind != FillKind::random || c.state.particles.size() == r.scene.fill.count;
    if (c.scene_name == r.scene.name && count_ok) {
      r.state = std::move(c.state);
      if (const auto choice = resolve_auto_search(r.scene, r.state.particles, r.state.dt)) {
        cli::print_auto_choice(*choice);
      }
      r.origin = fmt::format("cached {} (t = {:.4g} s)", file.string(), r.state.time);
      return r;
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  r.state = make_rolling(r.scene, settle, plan.turn_revolutions);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.origin = fmt::format("made in {:.1f} s: settle {:.3g} s, turn {:.3g} rev", seconds, settle,
                         plan.turn_revolutions);
  if (r.state.steps == 0) return r;  // nothing simulated: the fill is cheaper than a cache
  make_output_dir(plan.cache_dir);
  write_checkpoint(file, r.state, r.scene.name);
  write_file_atomically(key_file, [&](std::ostream& os) { os << key; });
  r.origin += fmt::format(", cached as {}", file.string());
  return r;
}

std::size_t heap_bytes_in_use() {
  return drumlab::heap_bytes_in_use();
}

std::size_t peak_rss_bytes() {
  struct rusage u {};
  ::getrusage(RUSAGE_SELF, &u);
  return static_cast<std::size_t>(u.ru_maxrss) * 1024;  // Linux: kilobytes
}

void warm_up(Simulation& sim, std::uint64_t steps) {
  sim.advance(steps);
  if (sim.scene().performance.sort_every > 0) sim.reorder_particles();
}

void make_output_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw InputError(fmt::format("{}: cannot create the output directory ({})", dir.string(),
                                 ec ? ec.message() : "not a directory"));
  }
}

}  // namespace drumlab::bench
