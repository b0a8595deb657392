#include "app/cli/run_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "app/cli/output_observers.hpp"
#include "app/cli/run_report.hpp"
#include "app/cli/scene_setup.hpp"
#include "engine/fill/file_fill.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/search/auto_select.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab::cli {

namespace {

/// Steps of the turning phase: --steps, --revolutions, or the scene's duration/revolutions.
std::uint64_t turning_steps(const RunOptions& opt, const SceneConfig& scene, double dt) {
  if (opt.steps) return *opt.steps;  // 0 too: fill and settle only, as LAMMPS's `run 0`
  const double omega = std::abs(scene.drum.omega);
  double seconds = 0.0;
  if (opt.revolutions > 0.0 || scene.time.revolutions) {
    const double revs = opt.revolutions > 0.0 ? opt.revolutions : *scene.time.revolutions;
    if (omega == 0.0) {
      throw InputError(fmt::format("{}: drum.omega: revolutions need a turning drum", opt.scene));
    }
    seconds = revs * 2.0 * std::numbers::pi / omega;
  } else if (scene.time.duration) {
    seconds = *scene.time.duration;
  } else {
    throw InputError(fmt::format(
        "{}: time: set duration or revolutions in the scene, or pass --steps/--revolutions",
        opt.scene));
  }
  return static_cast<std::uint64_t>(std::ceil(seconds / dt));
}

/// Advances `steps` in chunks no longer than the diagnostics interval and the frame interval;
/// returns the seconds spent in the observers.
double advance_phase(Simulation& sim, std::uint64_t steps, const std::string& label,
                     std::uint64_t every, std::span<FrameObserver* const> observers) {
  ProgressBar bar(label, steps);
  const std::uint64_t chunk = std::max<std::uint64_t>(1, sim.scene().output.diagnostics_every);
  std::uint64_t frame = 0;
  double output_seconds = 0.0;
  auto emit = [&] {
    // No frame of a bad state: a writer sees only a state that has just passed the stability
    // check (finite, inside the drum, sane overlaps), also for frame 0 of a restart.
    sim.check_stability();
    const auto t0 = std::chrono::steady_clock::now();
    for (FrameObserver* o : observers) o->on_frame(sim, frame);
    ++frame;
    output_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  if (every > 0) emit();
  for (std::uint64_t done = 0; done < steps;) {
    std::uint64_t n = std::min(chunk, steps - done);
    if (every > 0) n = std::min(n, every - done % every);
    sim.advance(n);
    done += n;
    if (every > 0 && done % every == 0) emit();
    bar.update(done);
  }
  bar.finish();
  return output_seconds;
}

}  // namespace

void add_run_options(CLI::App* cmd, RunOptions& opt) {
  cmd->add_option("--method", opt.method,
                  fmt::format("contact search method (overrides the scene): {}, or auto",
                              search_method_help()));
  auto* steps = cmd->add_option(
      "--steps", opt.steps,
      "turning steps after settling (0: only fill and settle, e.g. for --checkpoint)");
  cmd->add_option("--revolutions", opt.revolutions, "drum revolutions after settling")
      ->check(CLI::PositiveNumber)
      ->excludes(steps);
  cmd->add_option("--dt-factor", opt.dt_factor, "time step as a fraction of the Rayleigh time")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--settle-time", opt.settle_time, "seconds of settling (default: the scene's)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", opt.threads, "OpenMP threads")->check(CLI::Range(1, 1024));
  cmd->add_flag("--unsafe-dt", opt.unsafe_dt, "allow a time step above the Rayleigh time");
  cmd->add_option("--sort-every", opt.sort_every,
                  "re-order particles in memory every K steps, 0: never (overrides the scene)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--skin", opt.skin, "Verlet skin in smallest radii (overrides the scene)")
      ->check(CLI::Range(1e-6, 10.0));
  cmd->add_option("--vtu", opt.vtu_dir, "write a VTU/PVD series for ParaView into DIR");
  cmd->add_flag("--contacts-vtk", opt.contacts_vtk, "with --vtu: contacts as lines (.vtp)");
  cmd->add_flag("--grid-vtk", opt.grid_vtk, "with --vtu: search grid occupancy (.vti)");
  cmd->add_option("--h5", opt.h5_file, "write an HDF5 time series (+ XDMF sidecar) to FILE");
  cmd->add_option("--checkpoint", opt.checkpoint, "write a restart checkpoint (HDF5) at the end");
  cmd->add_option("--checkpoint-every", opt.checkpoint_every,
                  "also rewrite the checkpoint every K steps")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--restart", opt.restart,
                  "continue from a checkpoint (no fill, no settling) for the requested steps");
}

namespace {

/// The simulation to run: a fresh fill, or the state of a checkpoint (--restart).
/// Replaces search "auto" by the method chosen for these particles, and says why.
void resolve_auto_search(SceneConfig& scene, const RunOptions& opt, const Particles& particles,
                         double dt) {
  if (scene.search_method != "auto") return;
  if (dt <= 0.0) {
    dt = scene.time.dt.value_or((opt.dt_factor > 0.0 ? opt.dt_factor : scene.time.dt_factor) *
                                rayleigh_time(scene.min_radius(), scene.material));
  }
  const SearchChoice choice = choose_search_method(scene, dt, particles.position, particles.radius);
  fmt::print("search auto       -> {}: {}\n", choice.method, choice.reason);
  scene.search_method = choice.method;
}

std::unique_ptr<Simulation> make_simulation(const RunOptions& opt, SceneConfig scene) {
  if (opt.restart.empty()) {
    SimulationOptions sim_options;
    sim_options.allow_unsafe_dt = opt.unsafe_dt;
    sim_options.dt_factor_override = opt.dt_factor;
    Particles particles = initial_fill(scene);
    resolve_auto_search(scene, opt, particles, 0.0);
    return std::make_unique<Simulation>(scene, std::move(particles), sim_options);
  }
  Checkpoint c = read_checkpoint(opt.restart);
  if (c.scene_name != scene.name) {
    fmt::print("note: {} was written by scene '{}', continuing with scene '{}'\n", opt.restart,
               c.scene_name, scene.name);
  }
  if (opt.dt_factor > 0.0)
    fmt::print("note: --restart keeps the checkpoint's dt; --dt-factor ignored\n");
  if (!opt.method.empty()) {
    scene.search_method = opt.method;
    resolve_auto_search(scene, opt, c.state.particles, c.state.dt);
  }
  const std::string method = scene.search_method;
  auto sim = std::make_unique<Simulation>(scene, std::move(c.state));
  if (!opt.method.empty()) sim->set_search_method(method);
  fmt::print("restart           {} (step {}, t = {:.6g} s)\n", opt.restart, sim->steps(),
             sim->time());
  return sim;
}

}  // namespace

void run_session(const RunOptions& opt, std::span<FrameObserver* const> extra_observers) {
  SceneConfig scene = load_dynamic_scene(opt.scene);
  if (!opt.method.empty()) {
    if (opt.method != "auto") {
      try {
        make_search(opt.method);
      } catch (const InputError& e) {
        throw InputError(fmt::format("--method: {}", e.what()));
      }
    }
    scene.search_method = opt.method;
  }
  if (opt.sort_every >= 0) {
    scene.performance.sort_every = static_cast<std::uint64_t>(opt.sort_every);
  }
  if (opt.skin > 0.0) scene.performance.verlet_skin = opt.skin;
#ifdef _OPENMP
  omp_set_num_threads(opt.threads);
#endif
  const std::vector<std::unique_ptr<FrameObserver>> outputs = make_output_observers(opt);
  std::vector<FrameObserver*> observers(extra_observers.begin(), extra_observers.end());
  for (const auto& o : outputs) observers.push_back(o.get());
  const std::unique_ptr<Simulation> sim_ptr = make_simulation(opt, scene);
  Simulation& sim = *sim_ptr;
  const std::uint64_t turn_steps = turning_steps(opt, scene, sim.dt());
  const double settle_time = !opt.restart.empty()     ? 0.0
                             : opt.settle_time >= 0.0 ? opt.settle_time
                                                      : scene.fill.settle_time;
  const auto settle_steps = static_cast<std::uint64_t>(std::ceil(settle_time / sim.dt()));
  std::uint64_t every = opt.every;
  if (every == 0 && opt.frames > 0) every = std::max<std::uint64_t>(1, turn_steps / opt.frames);
  if (every == 0 && !observers.empty()) every = std::max<std::uint64_t>(1, turn_steps / 100);

  fmt::print("scene             {} ({})\n", scene.name, opt.scene);
  fmt::print(
      "plan              settle {} steps ({:.3g} s, drum at rest), then turn {} steps ({:.3g} s, "
      "{:.3g} rev)\n",
      settle_steps, settle_time, turn_steps, static_cast<double>(turn_steps) * sim.dt(),
      static_cast<double>(turn_steps) * sim.dt() * std::abs(scene.drum.omega) /
          (2.0 * std::numbers::pi));
  if (settle_steps > 0) {
    sim.set_drum_omega(0.0);
    advance_phase(sim, settle_steps, "settle", 0, {});
    sim.set_drum_omega(scene.drum.omega);
  }
  PhaseMeter meter(sim);
  const double output_seconds =
      advance_phase(sim, turn_steps, "turn", observers.empty() ? 0 : every, observers);
  PhaseStats stats = meter.finish();
  stats.output_seconds = output_seconds;
  for (FrameObserver* o : observers) o->on_finish(sim);
  fmt::print("-- turning phase --\n");
  print_summary(sim, stats);
}

}  // namespace drumlab::cli
