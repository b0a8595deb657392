// drumlab run SCENE [--method M] [--steps N | --revolutions R] [--dt-factor F] [--threads N]
// drumlab demo      (the demo drum, scenes/drum_demo.toml)
// Fill, settle with the drum at rest, then turn the drum; report throughput and the time split.
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "app/cli/commands.hpp"
#include "app/cli/run_report.hpp"
#include "app/cli/scene_setup.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/simulation.hpp"

namespace drumlab::cli {

namespace {

struct RunOptions {
  std::string scene;
  std::string method;
  std::uint64_t steps = 0;
  double revolutions = 0.0;
  double dt_factor = 0.0;
  int threads = 1;
  bool unsafe_dt = false;
  double settle_time = -1.0;  ///< < 0: the scene's
};

/// Steps of the turning phase: --steps, --revolutions, or the scene's duration/revolutions.
std::uint64_t turning_steps(const RunOptions& opt, const SceneConfig& scene, double dt) {
  if (opt.steps > 0) return opt.steps;
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

void advance_with_progress(Simulation& sim, std::uint64_t steps, const std::string& label) {
  ProgressBar bar(label, steps);
  const std::uint64_t chunk = std::max<std::uint64_t>(1, sim.scene().output.diagnostics_every);
  for (std::uint64_t done = 0; done < steps;) {
    const std::uint64_t n = std::min(chunk, steps - done);
    sim.advance(n);
    done += n;
    bar.update(done);
  }
  bar.finish();
}

void run_scene(const RunOptions& opt) {
  SceneConfig scene = load_dynamic_scene(opt.scene);
  if (!opt.method.empty()) scene.search_method = opt.method;
#ifdef _OPENMP
  omp_set_num_threads(opt.threads);
#endif
  if (opt.threads > 1) {
    fmt::print("note: --threads {}: this version's step loop is serial; threads are not used yet\n",
               opt.threads);
  }
  Particles particles = random_fill(scene);
  SimulationOptions sim_options;
  sim_options.allow_unsafe_dt = opt.unsafe_dt;
  sim_options.dt_factor_override = opt.dt_factor;
  Simulation sim(scene, std::move(particles), sim_options);
  const std::uint64_t turn_steps = turning_steps(opt, scene, sim.dt());
  const double settle_time = opt.settle_time >= 0.0 ? opt.settle_time : scene.fill.settle_time;
  const auto settle_steps = static_cast<std::uint64_t>(std::ceil(settle_time / sim.dt()));

  fmt::print("scene             {} ({})\n", scene.name, opt.scene);
  fmt::print(
      "plan              settle {} steps ({:.3g} s, drum at rest), then turn {} steps ({:.3g} s, "
      "{:.3g} rev)\n",
      settle_steps, settle_time, turn_steps, static_cast<double>(turn_steps) * sim.dt(),
      static_cast<double>(turn_steps) * sim.dt() * std::abs(scene.drum.omega) /
          (2.0 * std::numbers::pi));
  if (settle_steps > 0) {
    sim.set_drum_omega(0.0);
    advance_with_progress(sim, settle_steps, "settle");
    sim.set_drum_omega(scene.drum.omega);
  }
  PhaseMeter meter(sim);
  advance_with_progress(sim, turn_steps, "turn");
  fmt::print("-- turning phase --\n");
  print_summary(sim, meter.finish());
}

void add_run_options(CLI::App* cmd, RunOptions& opt) {
  cmd->add_option("--method", opt.method,
                  "contact search method (overrides the scene): brute, m1..m5");
  auto* steps = cmd->add_option("--steps", opt.steps, "turning steps after settling");
  cmd->add_option("--revolutions", opt.revolutions, "drum revolutions after settling")
      ->check(CLI::PositiveNumber)
      ->excludes(steps);
  cmd->add_option("--dt-factor", opt.dt_factor, "time step as a fraction of the Rayleigh time")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--settle-time", opt.settle_time, "seconds of settling (default: the scene's)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", opt.threads, "OpenMP threads")->check(CLI::Range(1, 1024));
  cmd->add_flag("--unsafe-dt", opt.unsafe_dt, "allow a time step above the Rayleigh time");
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* run =
      app.add_subcommand("run", "Simulate a scene: fill, settle, turn the drum, report");
  run->add_option("scene", opt->scene, "scene file (TOML)")->required();
  add_run_options(run, *opt);
  run->callback([opt] { run_scene(*opt); });

  auto demo_opt = std::make_shared<RunOptions>();
  CLI::App* demo = app.add_subcommand("demo", "Run the demo drum (scenes/drum_demo.toml)");
  add_run_options(demo, *demo_opt);
  demo->callback([demo_opt] {
    demo_opt->scene = shipped_scene("drum_demo.toml");
    run_scene(*demo_opt);
  });
}

}  // namespace drumlab::cli
