#include "app/run/run_options.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "app/run/count_option.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab::cli {

void add_run_options(CLI::App* cmd, RunOptions& opt) {
  cmd->add_option("--method", opt.method,
                  fmt::format("contact search method (overrides the scene): {}, or auto",
                              search_method_help()));
  auto* steps = cmd->add_option(
      "--steps", opt.steps,
      "turning steps after settling (0: only fill and settle, e.g. for --checkpoint)");
  steps->check(whole_count());
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
  cmd->add_option(
         "--frame", opt.frame,
         "a planetary drum's frame for --vtu (default: drum, the engine's) and for "
         "render's pictures (default: carrier, turning with the arm): drum, lab or carrier")
      ->check(CLI::IsMember({"drum", "lab", "carrier"}));
  cmd->add_flag("--grid-vtk", opt.grid_vtk, "with --vtu: search grid occupancy (.vti)");
  cmd->add_option("--h5", opt.h5_file, "write an HDF5 time series (+ XDMF sidecar) to FILE");
  cmd->add_option("--agglomerates", opt.agglomerates,
                  "write agglomerate statistics per frame to FILE.csv and their chart to FILE.png");
  add_granule_flags(cmd, opt.granule);
  cmd->add_option("--observables", opt.observables,
                  "write the drum observables per frame (angle of repose by surface fit and by "
                  "centre of mass, flowing layer, liquid) to FILE.csv");
  cmd->add_option("--checkpoint", opt.checkpoint, "write a restart checkpoint (HDF5) at the end");
  cmd->add_option("--checkpoint-every", opt.checkpoint_every,
                  "also rewrite the checkpoint every K turning steps")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--restart", opt.restart,
                  "continue from a checkpoint (no fill, no settling) for the requested steps");
}

void add_run_arguments(CLI::App* run, RunOptions& opt) {
  run->add_option("scene", opt.scene, "scene file (TOML)")->required();
  add_run_options(run, opt);
  run->add_option("--every", opt.every,
                  "steps between the frames of --h5, --vtu, --agglomerates and --observables "
                  "(default: 1/100 of the turn)")
      ->check(CLI::PositiveNumber);
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

namespace {

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ea, eb;
  const auto pa = std::filesystem::weakly_canonical(a, ea);
  const auto pb = std::filesystem::weakly_canonical(b, eb);
  if (ea || eb) {
    return std::filesystem::absolute(a).lexically_normal() ==
           std::filesystem::absolute(b).lexically_normal();
  }
  return pa == pb;
}

}  // namespace

void check_run_options(const RunOptions& opt, bool frames_taken) {
  if (!opt.method.empty() && opt.method != "auto") {
    try {
      make_search(opt.method);
    } catch (const InputError& e) {
      throw InputError(fmt::format("--method: {}", e.what()));
    }
  }
  if (opt.vtu_dir.empty() && (opt.contacts_vtk || opt.grid_vtk)) {
    throw InputError("--contacts-vtk and --grid-vtk add to the VTU series: give --vtu DIR");
  }
  if (!opt.frame.empty() && opt.vtu_dir.empty() && !frames_taken) {
    throw InputError(
        "--frame: the frame of the VTU series (or of render's pictures): give --vtu DIR");
  }
  if (opt.checkpoint.empty() && opt.checkpoint_every > 0) {
    throw InputError("--checkpoint-every needs --checkpoint FILE");
  }
  if (opt.every > 0 && !opt.frame_outputs() && !frames_taken) {
    throw InputError(
        "--every: no output takes frames (give --h5 FILE, --vtu DIR, --agglomerates FILE or "
        "--observables FILE; the checkpoint keeps --checkpoint-every)");
  }
  check_granule_flags(opt.granule);
  if (!opt.h5_file.empty() && !opt.checkpoint.empty() && same_file(opt.h5_file, opt.checkpoint)) {
    throw InputError(fmt::format("--h5 and --checkpoint both name {}", opt.h5_file));
  }
}

void check_run_options_for(const RunOptions& opt, const SceneConfig& scene) {
  if (opt.frame == "carrier" && !scene.drum.orbit.active()) {
    throw InputError(fmt::format("{}: --frame carrier: the scene has no [drum.orbit]", opt.scene));
  }
}

}  // namespace drumlab::cli
