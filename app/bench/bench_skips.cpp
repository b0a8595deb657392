#include "app/bench/bench_skips.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "app/cli/output_observers.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/scene/scene_features.hpp"
#include "engine/simulation.hpp"
#include "engine/threads.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/bench_chart.hpp"
#endif

namespace drumlab::bench {

using cli::make_output_observers;
using cli::RunOptions;

namespace {

/// One way to run the rolling state: physics, search method, writers on or off.
struct Variant {
  SceneConfig scene;
  std::string method;
  bool writers = false;
};

/// A skip and the general path it is measured against.
struct SkipCase {
  std::string name;     ///< short (chart label)
  std::string general;  ///< what the general path is
  Variant with_skip;
  Variant without_skip;
  bool same_physics = true;
  bool walls_only = false;  ///< compare the wall phase only (different physics)
  std::string note;
  /// Seconds per step, one per repeat: process CPU time and wall clock.
  std::vector<double> with_cpu, without_cpu, with_wall, without_wall;
  double max_dx = std::numeric_limits<double>::quiet_NaN();  ///< |x_with - x_without| / r_min
};

struct RunResult {
  double cpu_per_step = 0.0;   ///< process CPU s of stepping + writers (the wall timer: walls_only)
  double wall_per_step = 0.0;  ///< wall-clock s of stepping + writers, or the wall-phase timer
  std::vector<Vec3> position_by_id;
};

/// CPU seconds of this process (one thread runs: less disturbed by other processes than the wall
/// clock on a busy shared machine).
double process_cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

RunResult run_variant(const RollingState& rolling, const Variant& v, const SkipsBenchOptions& opt,
                      bool walls_only, const std::filesystem::path& scratch) {
  SimulationState state = rolling.state;
  state.search_method = v.method;
  // A law that keeps per-contact state (the zero-strength cohesion) starts from none.
  const std::size_t state_size = ContactModel(v.scene).pair_state_size();
  if (state.contact_state_size == 0 && state_size > 0) {
    state.contact_state_size = state_size;
    state.contact_state.assign(state.contact_col.size() * state_size, 0.0);
  }
  Simulation sim(v.scene, std::move(state));
  std::vector<std::unique_ptr<FrameObserver>> writers;
  if (v.writers) {
    std::filesystem::remove_all(scratch);
    make_output_dir(scratch);
    RunOptions o;
#ifdef DRUMLAB_WITH_RENDER
    o.vtu_dir = (scratch / "vtu").string();
#endif
    o.h5_file = (scratch / "series.h5").string();
    writers = make_output_observers(o);
  }
  const std::uint64_t every =
      opt.every > 0 ? opt.every : std::max<std::uint64_t>(1, opt.steps / 10);
  const StepTimers t0 = sim.timers();
  const auto start = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_seconds();
  std::uint64_t frame = 0;
  for (auto& w : writers) w->on_frame(sim, frame);
  for (std::uint64_t done = 0; done < opt.steps;) {
    const std::uint64_t n = std::min(every, opt.steps - done);
    sim.advance(n);
    done += n;
    ++frame;
    for (auto& w : writers) w->on_frame(sim, frame);
  }
  const double cpu = process_cpu_seconds() - cpu0;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writers.clear();  // closes the files (untimed, like the one-off end of a run)
  RunResult r;
  const double steps = static_cast<double>(opt.steps);
  const double walls = (sim.timers().walls - t0.walls) / steps;
  r.cpu_per_step = walls_only ? walls : cpu / steps;
  r.wall_per_step = walls_only ? walls : wall / steps;
  const Particles& p = sim.particles();
  r.position_by_id.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) r.position_by_id[p.id[i]] = p.position[i];
  return r;
}

double max_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

/// A case that sets one material coefficient (material and wall) to 0 for the skip and to `tiny`
/// for the general path; rolling friction is 0 in both unless it is the coefficient.
SkipCase coefficient_case(const SceneConfig& base, const std::string& method, double tiny,
                          bool rolling) {
  SkipCase c;
  c.name = rolling ? "rolling 0" : "friction 0";
  c.general =
      fmt::format("{} {:g} (material and wall)", rolling ? "rolling_friction" : "friction", tiny);
  SceneConfig s = base;
  s.material.rolling_friction = s.wall.rolling_friction = 0.0;  // isolate the friction skip
  const auto set = [&](double v) {
    double& material = rolling ? s.material.rolling_friction : s.material.friction;
    double& wall = rolling ? s.wall.rolling_friction : s.wall.friction;
    material = wall = v;
  };
  set(0.0);
  c.with_skip = {s, method, false};
  set(tiny);
  c.without_skip = {s, method, false};
  c.note = rolling ? fmt::format("friction as in the scene ({}, wall {})", base.material.friction,
                                 base.wall.friction)
                   : "no tangential history, no rotation; rolling friction 0 in both";
  return c;
}

SkipCase grid_case(const SceneConfig& base, const char* grid3d) {
  const SceneFeatures f = scene_features(base);
  SkipCase c;
  c.name = fmt::format("2D grid m2 vs {}", grid3d);
  c.general = fmt::format("3D grid {}", grid3d);
  c.with_skip = {base, "m2", false};
  c.without_skip = {base, grid3d, false};
  c.note = f.shallow
               ? fmt::format("shallow: depth = {:.3g} largest diameters", f.depth_in_diameters)
               : fmt::format("deep ({:.3g} largest diameters): the skip does not apply",
                             f.depth_in_diameters);
  return c;
}

/// A case of two scenes run with `method`: the one the engine skips work in, and the general one.
SkipCase scene_pair_case(std::string name, std::string general, const SceneConfig& with_skip,
                         const SceneConfig& without_skip, const std::string& method,
                         std::string note) {
  SkipCase c;
  c.name = std::move(name);
  c.general = std::move(general);
  c.with_skip = {with_skip, method, false};
  c.without_skip = {without_skip, method, false};
  c.note = std::move(note);
  return c;
}

SkipCase ends_case(const SceneConfig& base, const std::string& method) {
  SceneConfig periodic = base;
  periodic.drum.ends = DrumEnds::periodic;
  SceneConfig caps = base;
  caps.drum.ends = DrumEnds::caps;
  SkipCase c = scene_pair_case("periodic ends", "end caps", periodic, caps, method,
                               "different physics: wall-phase time only");
  c.same_physics = false;
  c.walls_only = true;
  return c;
}

SkipCase cohesion_case(const SceneConfig& base, const std::string& method) {
  SceneConfig zero = base;
  zero.cohesion.enabled = true;
  zero.cohesion.energy_density = 0.0;
  return scene_pair_case("cohesion off", "[cohesion] sjkr with energy_density 0", base, zero,
                         method, "zero-strength adhesion: the cohesive pass runs, adds nothing");
}

SkipCase writers_case(const SceneConfig& base, const std::string& method) {
  SkipCase c;
  c.name = "no writers";
#ifdef DRUMLAB_WITH_RENDER
  c.general = "--vtu and --h5 writers";
#else
  c.general = "--h5 writer (no VTK in this build)";
#endif
  c.with_skip = {base, method, false};
  c.without_skip = {base, method, true};
  c.note = "stepping + writing";
  return c;
}

std::vector<SkipCase> make_cases(const SceneConfig& base, const std::string& method, double tiny) {
  std::vector<SkipCase> cases;
  cases.push_back(coefficient_case(base, method, tiny, false));
  cases.push_back(coefficient_case(base, method, tiny, true));
  for (const char* grid3d : {"m3", "m5"}) cases.push_back(grid_case(base, grid3d));
  // A periodic state may straddle the ends: no caps.
  if (base.drum.ends == DrumEnds::caps) cases.push_back(ends_case(base, method));
  if (!base.liquid.enabled && !base.cohesion.enabled) cases.push_back(cohesion_case(base, method));
  cases.push_back(writers_case(base, method));
  return cases;
}

void write_csv(const std::filesystem::path& file, const std::string& scene,
               const SkipsBenchOptions& opt, const std::vector<SkipCase>& cases) {
  write_file_atomically(file, [&](std::ostream& os) {
    os << "scene,skip,general_path,measure,steps,repeats,with_skip_cpu_s_per_step,"
          "without_skip_cpu_s_per_step,gain_cpu,with_skip_wall_s_per_step,"
          "without_skip_wall_s_per_step,gain_wall,same_physics,max_dx_over_rmin,note\n";
    for (const SkipCase& c : cases) {
      const double w = median(c.with_cpu), wo = median(c.without_cpu);
      const double ww = median(c.with_wall), wwo = median(c.without_wall);
      os << fmt::format(
          "{},{},{},{},{},{},{:.6g},{:.6g},{:.4g},{:.6g},{:.6g},{:.4g},{},{},\"{}\"\n", scene,
          c.name, c.general, c.walls_only ? "wall phase (wall clock)" : "step", opt.steps,
          opt.repeats, w, wo, wo / w, ww, wwo, wwo / ww, c.same_physics ? 1 : 0,
          std::isfinite(c.max_dx) ? fmt::format("{:.3g}", c.max_dx) : "", c.note);
    }
  });
}

void write_chart(const std::filesystem::path& file, const std::string& scene,
                 const std::vector<SkipCase>& cases) {
#ifdef DRUMLAB_WITH_RENDER
  std::vector<std::string> names;
  render::BarSeries with{"with the skip", {}}, without{"general path", {}}, gain{"gain", {}};
  for (const SkipCase& c : cases) {
    names.push_back(c.name);
    with.values.push_back(1e3 * median(c.with_cpu));
    without.values.push_back(1e3 * median(c.without_cpu));
    gain.values.push_back(median(c.without_cpu) / median(c.with_cpu));
  }
  render::BarPanel time{fmt::format("{}: CPU time per step (periodic: wall phase)", scene),
                        "ms per step (median)",
                        names,
                        {with, without},
                        true};
  render::BarPanel speedup{"gain = general / with skip", "x", names, {gain}, false};
  render::write_bar_charts({time, speedup}, file);
  fmt::print("wrote {}\n", file.string());
#else
  (void)scene, (void)cases;
  fmt::print("note: built without rendering: no chart {}\n", file.string());
#endif
}

void print_row(const SkipCase& c) {
  const double w = median(c.with_cpu), wo = median(c.without_cpu);
  const double wall_gain = median(c.without_wall) / median(c.with_wall);
  fmt::print("{:<18} {:>10.4g} {:>12.4g} {:>6.2f}x {:>8.2f}x {:>12} {:<38} {}\n", c.name, 1e3 * w,
             1e3 * wo, wo / w, wall_gain,
             c.same_physics ? fmt::format("{:.3g}", c.max_dx) : std::string("n/a"), c.general,
             c.note);
}

}  // namespace

void run_bench_skips(const SkipsBenchOptions& opt) {
  if (!(opt.tiny > 0.0) || !(opt.tiny < 1e-20)) {
    throw InputError(fmt::format("--tiny {}: must be in (0, 1e-20)", opt.tiny));
  }
  const std::filesystem::path out = opt.out;
  make_output_dir(out);
  set_thread_count(1);  // also for preparing the state: 2 threads on a busy 2-core VM crawl
  const RollingState rolling = rolling_state(opt.scene, opt.plan);
  const std::string& name = rolling.scene.name;
  const std::string method = rolling.state.search_method;
  fmt::print("scene             {} ({}), {} particles, 1 thread\n", name, opt.scene,
             rolling.state.particles.size());
  fmt::print("state             {}\n", rolling.origin);
  fmt::print(
      "run               {} steps per run, {} repeats (median), search {} unless named; "
      "writers every {} steps\n",
      opt.steps, opt.repeats, method,
      opt.every > 0 ? opt.every : std::max<std::uint64_t>(1, opt.steps / 10));
  std::vector<SkipCase> cases = make_cases(rolling.scene, method, opt.tiny);
  if (rolling.scene.drum.ends == DrumEnds::periodic) {
    fmt::print(
        "note              the scene has periodic ends: its state cannot be run with caps "
        "(particles straddle the ends), so the end-cap skip is not measured\n");
  }
  const auto scratch = out / fmt::format("skips_{}_writers", name);
  for (int r = 0; r < opt.repeats; ++r) {
    for (SkipCase& c : cases) {
      // Alternate the order so a machine getting busier does not favour one side.
      const bool skip_first = r % 2 == 0;
      RunResult a = run_variant(rolling, skip_first ? c.with_skip : c.without_skip, opt,
                                c.walls_only, scratch);
      RunResult b = run_variant(rolling, skip_first ? c.without_skip : c.with_skip, opt,
                                c.walls_only, scratch);
      if (!skip_first) std::swap(a, b);
      c.with_cpu.push_back(a.cpu_per_step);
      c.without_cpu.push_back(b.cpu_per_step);
      c.with_wall.push_back(a.wall_per_step);
      c.without_wall.push_back(b.wall_per_step);
      if (r == 0 && c.same_physics) {
        c.max_dx = max_difference(a.position_by_id, b.position_by_id) / rolling.scene.min_radius();
      }
    }
    fmt::print("repeat {}/{} done\n", r + 1, opt.repeats);
    std::fflush(stdout);
  }
  std::filesystem::remove_all(scratch);
  fmt::print("{:<18} {:>10} {:>12} {:>7} {:>9} {:>12} {:<38} {}\n", "skip", "with ms", "general ms",
             "gain", "wall gain", "max|dx|/rmin", "general path", "note");
  for (const SkipCase& c : cases) print_row(c);
  fmt::print(
      "ms: median CPU milliseconds per step of this (single-threaded) process, stepping and "
      "writers included; gain = general / with skip; wall gain: the same from the wall clock "
      "(includes waiting for the CPU on a busy machine, and for the disk); periodic ends: the "
      "engine's wall-phase timer (wall clock) for both. max|dx|/rmin: largest position difference "
      "after "
      "the run between the two paths, over the smallest radius (round-off when the physics "
      "is the same)\n");
  const auto csv = out / fmt::format("skips_{}.csv", name);
  write_csv(csv, name, opt, cases);
  fmt::print("wrote {}\n", csv.string());
  write_chart(out / fmt::format("skips_{}.png", name), name, cases);
}

}  // namespace drumlab::bench
