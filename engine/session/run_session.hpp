#pragma once
// One run of a scene, in the engine's world: fill (the scene's [fill] kind) or continue from a
// checkpoint, resolve search "auto", settle with the drum at rest, then turn the drum while
// scheduled observers read the state between steps (never inside the step loop). Used by the CLI
// (`run`, `demo`, `render`, `teach`), the benchmarks' rolling state and the stress suite; a GUI
// drives the same object from its own thread, step by step (`advance`), may switch the search
// method between steps and reads the simulation between calls. Nothing here prints: the choices
// made are returned as data, progress goes to a callback.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/search/auto_select.hpp"
#include "engine/session/phase_meter.hpp"
#include "engine/session/team_chooser.hpp"
#include "engine/simulation.hpp"

namespace drumlab {

/// Loads a dynamic scene (random or file fill). A static paper packing is refused with a clear
/// error naming the file.
SceneConfig load_dynamic_scene(const std::string& file);

/// A scheduled observer: called at the start of the turning phase (frame 0) and every
/// `every` steps after it, then once at the end. It reads the simulation and must not change it.
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  virtual void on_frame(const Simulation& sim, std::uint64_t frame) = 0;
  virtual void on_finish(const Simulation& /*sim*/) {}
  /// Steps between this observer's frames when it keeps a schedule of its own (a checkpoint
  /// every K steps); 0: the run's `every`.
  virtual std::uint64_t every() const { return 0; }
};

struct SessionOptions {
  std::string scene_file;        ///< names the scene in error messages (may be empty)
  std::string method;            ///< non-empty: replaces the scene's search method ("auto" too)
  double dt_factor = 0.0;        ///< > 0: time step as this fraction of the Rayleigh time
  bool unsafe_dt = false;        ///< allow a time step above the Rayleigh time
  std::int64_t sort_every = -1;  ///< >= 0: overrides performance.sort_every
  double skin = 0.0;             ///< > 0: overrides performance.verlet_skin
  double settle_time = -1.0;     ///< s with the drum at rest; < 0: fill.settle_time
  std::optional<std::uint64_t> steps;  ///< turning steps (0: fill and settle only)
  double revolutions = 0.0;            ///< > 0: turning length in drum revolutions
  std::string restart;                 ///< checkpoint file: no fill, no settling, its state and dt
  /// With more than one OpenMP thread: let a TeamChooser pick the team (N or 1 thread) for each
  /// window of steps by timing both (the same bits either way).
  bool adaptive_team = false;
  int team_probe_every =
      TeamChooser::kProbeEvery;  ///< windows between two timings of the other team
};

/// What a restart read from its checkpoint.
struct RestartInfo {
  std::string file;
  std::string checkpoint_scene;    ///< the scene name the checkpoint was written by
  bool dt_factor_ignored = false;  ///< a dt factor was asked: the checkpoint's dt is kept
};

struct SessionPlan {
  std::uint64_t settle_steps = 0;
  double settle_time = 0.0;  ///< s (0 for a restart)
  std::uint64_t turn_steps = 0;
};

/// Called after each chunk of steps of a phase with the steps done and the phase's total;
/// returning false stops the phase there.
using SessionProgress = std::function<bool(std::uint64_t done, std::uint64_t total)>;

struct TurnResult {
  PhaseStats stats;  ///< the turning phase (observers' time in stats.output_seconds)
  std::uint64_t frames = 0;
  bool stopped = false;  ///< the progress callback stopped it early
};

/// The scene with the options' overrides applied (search method, sort_every, Verlet skin): what a
/// RunSession runs, but for "auto", which it resolves on its particles.
SceneConfig scene_with_options(SceneConfig scene, const SessionOptions& options);

/// Settle and turn steps of a run with time step `dt` (a restart settles none): --steps,
/// --revolutions, or the scene's duration/revolutions. Throws InputError (naming the scene file)
/// when none gives the turning phase a length.
SessionPlan session_plan(const SceneConfig& scene, const SessionOptions& options, double dt,
                         bool restart);

/// If the scene's search is "auto", replaces it by the method chosen for these particles with
/// time step `dt` and returns the choice (method and reason); otherwise returns nothing.
std::optional<SearchChoice> resolve_auto_search(SceneConfig& scene, const Particles& particles,
                                                double dt);

class RunSession {
 public:
  /// Fills the scene (or reads options.restart), applies the overrides and resolves "auto".
  /// Throws InputError for bad input.
  RunSession(SceneConfig scene, SessionOptions options);
  /// Drives a simulation built elsewhere (drumlab-mpi: this rank's part of a decomposed run)
  /// for the scene as run (`scene`: overrides applied, "auto" already resolved, as `auto_choice`
  /// says); `restart`: it continues a checkpoint (no settling).
  RunSession(SceneConfig scene, SessionOptions options, std::unique_ptr<Simulation> sim,
             std::optional<RestartInfo> restart, std::optional<SearchChoice> auto_choice);
  RunSession(const RunSession&) = delete;
  RunSession& operator=(const RunSession&) = delete;

  /// The scene as run: overrides applied, "auto" replaced by the chosen method.
  const SceneConfig& scene() const { return scene_; }
  const SessionOptions& options() const { return options_; }
  Simulation& simulation() { return *sim_; }
  const Simulation& simulation() const { return *sim_; }
  /// The team chooser (options.adaptive_team with more than one thread), or null.
  const TeamChooser* team_chooser() const { return team_ ? &*team_ : nullptr; }
  /// Hands the simulation over (the session is then spent).
  std::unique_ptr<Simulation> release_simulation() { return std::move(sim_); }
  /// How "auto" was resolved (at construction or by the last set_search_method("auto")).
  const std::optional<SearchChoice>& auto_choice() const { return auto_choice_; }
  const std::optional<RestartInfo>& restart() const { return restart_; }

  /// Settle and turn steps: --steps, --revolutions, or the scene's duration/revolutions. Throws
  /// InputError (naming the scene file) when none gives the turning phase a length.
  SessionPlan plan() const;
  /// Settling steps only (never throws for a missing run length).
  std::uint64_t settle_steps() const;

  /// Runs the settling steps with the drum at rest, then restores its angular velocity.
  void settle(const SessionProgress& progress = {});
  /// Advances `n` steps in chunks of at most output.diagnostics_every; returns the steps done.
  std::uint64_t advance(std::uint64_t n, const SessionProgress& progress = {});
  /// Turns `steps` steps; each observer with a schedule (its own `every()`, else `every` > 0)
  /// sees frame 0 now and a frame every that many steps (each after the stability check); every
  /// observer sees on_finish at the end. The chunks of steps end at every scheduled frame.
  TurnResult run_turn(std::uint64_t steps, std::uint64_t every,
                      std::span<FrameObserver* const> observers,
                      const SessionProgress& progress = {});
  /// Switches the search between steps; "auto" chooses again on the current state.
  void set_search_method(const std::string& name);

 private:
  /// Advances `n` steps in chunks that end at each multiple of every non-zero `every` (steps
  /// counted from this call) and calls `after_chunk` with the steps done after each chunk.
  std::uint64_t advance_chunked(std::uint64_t n, std::span<const std::uint64_t> every,
                                const std::function<void(std::uint64_t)>& after_chunk,
                                const SessionProgress& progress);

  SceneConfig scene_;
  SessionOptions options_;
  std::unique_ptr<Simulation> sim_;
  std::optional<TeamChooser> team_;
  std::optional<SearchChoice> auto_choice_;
  std::optional<RestartInfo> restart_;
};

}  // namespace drumlab
