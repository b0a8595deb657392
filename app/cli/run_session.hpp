#pragma once
// The run loop shared by `run`, `demo` and `render`: load a scene, fill, settle with the drum at
// rest, turn the drum, and call scheduled observers (writers, renderers) between steps — never
// inside the step loop.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <CLI/CLI.hpp>

#include "engine/simulation.hpp"

namespace drumlab::cli {

struct RunOptions {
  std::string scene;
  std::string method;
  std::optional<std::uint64_t> steps;  ///< --steps (0: fill and settle only)
  double revolutions = 0.0;
  double dt_factor = 0.0;
  int threads = 1;
  bool unsafe_dt = false;
  std::int64_t sort_every = -1;  ///< >= 0: overrides performance.sort_every
  double skin = 0.0;             ///< > 0: overrides performance.verlet_skin
  double settle_time = -1.0;     ///< < 0: the scene's fill.settle_time
  std::uint64_t every = 0;       ///< steps between frames for observers (0: the run decides)
  std::uint64_t frames = 0;      ///< if > 0, spread this many frames over the turning phase
  // Outputs (see output_observers.hpp).
  std::string vtu_dir;        ///< --vtu DIR
  bool contacts_vtk = false;  ///< --contacts-vtk
  bool grid_vtk = false;      ///< --grid-vtk
  std::string h5_file;        ///< --h5 FILE
  std::string checkpoint;     ///< --checkpoint FILE (written at the end)
  std::uint64_t checkpoint_every = 0;
  std::string restart;  ///< --restart FILE: skip fill and settling, continue from the file
};

/// A scheduled observer: called at the start of the turning phase (frame 0) and every
/// `every` steps after it, then once at the end. It reads the simulation and must not change it.
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  virtual void on_frame(const Simulation& sim, std::uint64_t frame) = 0;
  virtual void on_finish(const Simulation& /*sim*/) {}
};

/// Adds the options of RunOptions (except the scene and the frame schedule --every/--frames, which
/// each command adds itself) to a subcommand.
void add_run_options(CLI::App* cmd, RunOptions& opt);

/// Runs the scene as planned by `opt` and prints the summary of the turning phase. The output
/// writers requested in `opt` are added to `observers`.
void run_session(const RunOptions& opt, std::span<FrameObserver* const> observers = {});

}  // namespace drumlab::cli
