#include "app/cli/run_session.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "app/cli/output_observers.hpp"
#include "app/cli/run_report.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/threads.hpp"

namespace drumlab::cli {

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
  cmd->add_option("--team", opt.team,
                  "with --threads N > 1: adaptive (time N and 1 thread now and then, run the "
                  "faster; the same results) or fixed (always N)")
      ->check(CLI::IsMember({"adaptive", "fixed"}));
  cmd->add_option("--team-probe-every", opt.team_probe_every,
                  "adaptive team: windows of 100 steps between two timings of the other team")
      ->check(CLI::Range(1, 1000000));
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
  cmd->add_option("--agglomerates", opt.agglomerates,
                  "write agglomerate statistics per frame to FILE.csv and their chart to FILE.png");
  cmd->add_option("--granule-age", opt.granule_age,
                  "granule criterion: bonds older than T s join (0: plain components; default: "
                  "one drum revolution)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--checkpoint", opt.checkpoint, "write a restart checkpoint (HDF5) at the end");
  cmd->add_option("--checkpoint-every", opt.checkpoint_every,
                  "also rewrite the checkpoint every K steps")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--restart", opt.restart,
                  "continue from a checkpoint (no fill, no settling) for the requested steps");
}

SessionOptions session_options(const RunOptions& opt) {
  SessionOptions o;
  o.scene_file = opt.scene;
  o.method = opt.method;
  o.dt_factor = opt.dt_factor;
  o.unsafe_dt = opt.unsafe_dt;
  o.sort_every = opt.sort_every;
  o.skin = opt.skin;
  o.settle_time = opt.settle_time;
  o.steps = opt.steps;
  o.revolutions = opt.revolutions;
  o.restart = opt.restart;
  o.adaptive_team = opt.team == "adaptive";
  o.team_probe_every = opt.team_probe_every;
  return o;
}

void print_auto_choice(const SearchChoice& choice) {
  fmt::print("search auto       -> {}: {}\n", choice.method, choice.reason);
}

void print_session_choices(const RunSession& session) {
  if (const auto& r = session.restart()) {
    if (r->checkpoint_scene != session.scene().name) {
      fmt::print("note: {} was written by scene '{}', continuing with scene '{}'\n", r->file,
                 r->checkpoint_scene, session.scene().name);
    }
    if (r->dt_factor_ignored)
      fmt::print("note: --restart keeps the checkpoint's dt; --dt-factor ignored\n");
  }
  if (const auto& choice = session.auto_choice()) print_auto_choice(*choice);
  if (const auto& r = session.restart()) {
    const Simulation& sim = session.simulation();
    fmt::print("restart           {} (step {}, t = {:.6g} s)\n", r->file, sim.steps(), sim.time());
  }
}

void run_session(const RunOptions& opt, std::span<FrameObserver* const> extra_observers) {
  const SceneConfig scene = load_dynamic_scene(opt.scene);
  if (!opt.method.empty() && opt.method != "auto") {
    try {
      make_search(opt.method);
    } catch (const InputError& e) {
      throw InputError(fmt::format("--method: {}", e.what()));
    }
  }
  set_thread_count(opt.threads);
  const std::vector<std::unique_ptr<FrameObserver>> outputs = make_output_observers(opt);
  std::vector<FrameObserver*> observers(extra_observers.begin(), extra_observers.end());
  for (const auto& o : outputs) observers.push_back(o.get());
  RunSession session(scene, session_options(opt));
  print_session_choices(session);
  const Simulation& sim = session.simulation();
  const SessionPlan plan = session.plan();
  std::uint64_t every = opt.every;
  if (every == 0 && opt.frames > 0)
    every = std::max<std::uint64_t>(1, plan.turn_steps / opt.frames);
  if (every == 0 && !observers.empty()) every = std::max<std::uint64_t>(1, plan.turn_steps / 100);

  fmt::print("scene             {} ({})\n", session.scene().name, opt.scene);
  fmt::print(
      "plan              settle {} steps ({:.3g} s, drum at rest), then turn {} steps ({:.3g} s, "
      "{:.3g} rev)\n",
      plan.settle_steps, plan.settle_time, plan.turn_steps,
      static_cast<double>(plan.turn_steps) * sim.dt(),
      static_cast<double>(plan.turn_steps) * sim.dt() * std::abs(scene.drum.omega) /
          (2.0 * std::numbers::pi));
  settle_with_progress(session, plan.settle_steps);
  ProgressBar bar("turn", plan.turn_steps);
  const TurnResult turn = session.run_turn(plan.turn_steps, observers.empty() ? 0 : every,
                                           observers, [&](std::uint64_t done, std::uint64_t) {
                                             bar.update(done);
                                             return true;
                                           });
  bar.finish();
  fmt::print("-- turning phase --\n");
  print_summary(sim, turn.stats);
  if (const TeamChooser* t = session.team_chooser()) {
    fmt::print(
        "team              {} (settling and turning; the faster team runs; `--team fixed`: always "
        "{})\n",
        team_report(*t), t->threads());
  }
}

}  // namespace drumlab::cli
