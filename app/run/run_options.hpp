#pragma once
// The options of `run` (`drumlab run` and `drumlab-mpi run`; `demo` and `render` take them too):
// one struct and the one function that declares them on a CLI11 command, so that both executables
// accept the same flags with the same checks.
#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/run/granule_flags.hpp"
#include "engine/session/run_session.hpp"

namespace drumlab::cli {

struct RunOptions {
  std::string scene;
  std::string method;
  std::optional<std::uint64_t> steps;  ///< --steps (0: fill and settle only)
  double revolutions = 0.0;
  double dt_factor = 0.0;
  int threads = 1;
  std::string team = "adaptive";                    ///< --team: adaptive or fixed (see TeamChooser)
  int team_probe_every = TeamChooser::kProbeEvery;  ///< --team-probe-every
  bool unsafe_dt = false;
  std::int64_t sort_every = -1;  ///< >= 0: overrides performance.sort_every
  double skin = 0.0;             ///< > 0: overrides performance.verlet_skin
  double settle_time = -1.0;     ///< < 0: the scene's fill.settle_time
  std::uint64_t every = 0;       ///< steps between frames for observers (0: the run decides)
  std::uint64_t frames = 0;      ///< if > 0, spread this many frames over the turning phase
  // Outputs (app/run/output_schedule.hpp).
  std::string vtu_dir;        ///< --vtu DIR
  bool contacts_vtk = false;  ///< --contacts-vtk
  /// --frame drum|lab|carrier (view_frame.hpp); "": the default of each output (vtu_frame()).
  std::string frame;
  bool grid_vtk = false;   ///< --grid-vtk
  std::string h5_file;     ///< --h5 FILE
  std::string checkpoint;  ///< --checkpoint FILE (written at the end)
  std::uint64_t checkpoint_every = 0;
  std::string agglomerates;  ///< --agglomerates FILE.csv (+ FILE.png)
  GranuleFlags granule;      ///< --granule-criterion, --granule-age, --granule-resolution
  std::string observables;   ///< --observables FILE.csv (observable_rows.hpp)
  std::string restart;       ///< --restart FILE: skip fill and settling, continue from the file

  /// The VTU series' frame: --frame, by default the drum's (the engine's).
  std::string vtu_frame() const { return frame.empty() ? "drum" : frame; }
  /// Whether an output takes frames (--h5, --vtu, --agglomerates, --observables).
  bool frame_outputs() const {
    return !h5_file.empty() || !vtu_dir.empty() || !agglomerates.empty() || !observables.empty();
  }
};

/// Adds the options of RunOptions (except the scene and the frame schedule --every/--frames, which
/// each command adds itself) to a subcommand.
void add_run_options(CLI::App* cmd, RunOptions& opt);

/// `run`'s arguments: the scene, add_run_options and --every. Declared by `drumlab run` and
/// `drumlab-mpi run` alike.
void add_run_arguments(CLI::App* run, RunOptions& opt);

/// The session options `opt` asks for (the scene file, method, time step, settling, restart...).
SessionOptions session_options(const RunOptions& opt);

/// Throws InputError (one line naming the flag) for options that contradict each other or name
/// an unknown search method: --checkpoint-every without --checkpoint, --every with no output
/// that takes frames (`frames_taken`: the command has frame observers of its own, as `render`),
/// --contacts-vtk/--grid-vtk without --vtu, --h5 and --checkpoint naming one file.
void check_run_options(const RunOptions& opt, bool frames_taken = false);
/// The checks that need the scene: --frame carrier only with [drum.orbit].
void check_run_options_for(const RunOptions& opt, const SceneConfig& scene);

}  // namespace drumlab::cli
