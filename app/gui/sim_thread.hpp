#pragma once
// The workbench's simulation thread: it owns the RunSession, steps it in chunks (settling first,
// as the CLI does), and after every chunk takes a FrameSnapshot (render::view_snapshot) that it
// hands to the UI thread under a mutex. The UI never reads the Simulation; it sends commands
// (run, pause, single step, switch method, restart from an edited scene, change what the snapshot
// holds), which the thread applies between steps.
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "engine/session/frame_snapshot.hpp"
#include "engine/session/run_session.hpp"
#include "render/drum_view.hpp"

namespace drumlab::gui {

/// What the snapshot must carry (the view's colour-by and focus, the teaching mode's methods).
struct SnapshotWish {
  render::ViewOptions view;
  std::vector<std::string> compare_methods;
};

/// A method switch at an exact step (sim.steps() == step): --switch-at K:METHOD.
struct ScheduledSwitch {
  std::uint64_t step = 0;
  std::string method;
};

class SimThread {
 public:
  /// Builds the session on the calling thread (fill, auto), so bad input throws here
  /// (InputError), then starts the thread paused. `step_limit` > 0: stop for good once the
  /// simulation has made that many steps (headless runs).
  /// `threads`: the simulation's OpenMP threads (set on the simulation thread itself: the count
  /// is per thread).
  SimThread(SceneConfig scene, SessionOptions options, SnapshotWish wish, int threads,
            std::optional<ScheduledSwitch> scheduled = {}, std::uint64_t step_limit = 0);
  ~SimThread();
  SimThread(const SimThread&) = delete;
  SimThread& operator=(const SimThread&) = delete;

  /// The newest snapshot (nullptr before the first) and a counter that grows with every new one.
  /// While running, a snapshot is taken after a chunk only once the last one has been taken.
  std::shared_ptr<const FrameSnapshot> latest() const;
  std::uint64_t generation() const;

  void set_running(bool running);
  bool running() const;
  /// One chunk of steps (paused only).
  void single_step();
  /// Steps per chunk (a snapshot after each).
  void set_chunk(std::uint64_t steps);
  /// Switches the search method before the next step ("auto" chooses again).
  void switch_method(const std::string& name);
  /// Throws away the run and starts again from `scene` (filled and settled anew), paused.
  void restart(SceneConfig scene);
  /// What the next snapshots carry; a new snapshot is taken now if the thread is idle.
  void set_wish(SnapshotWish wish);
  /// Runs `job` on the simulation between steps (an export that needs the full state) and waits.
  void with_simulation(const std::function<void(const Simulation&)>& job);

  /// The scene as run (overrides applied, "auto" resolved) as of the last restart or method
  /// switch: a copy the simulation thread publishes under the lock, safe to read from any thread.
  SceneConfig scene() const;
  /// "settling 120 / 1000 steps", "running", "paused", "done", or the error that stopped it.
  std::string state_text() const;
  /// True once step_limit is reached (or the run stopped on an error).
  bool finished() const;
  /// Particle-steps per second of the stepping alone (wall time inside advance/settle).
  double particle_steps_per_second() const;
  /// Particle-steps made and wall seconds spent stepping, since the start.
  std::pair<double, double> stepping_totals() const;
  /// With an adaptive team (SessionOptions::adaptive_team): a copy of its chooser as of the last
  /// steps (the team now, the windows each team ran); none with a fixed team.
  std::optional<TeamChooser> team() const;
  /// True once the settling phase is over.
  bool settled() const;
  /// Waits until finished() (headless runs).
  void wait_finished() const;

 private:
  // The locking discipline: the simulation thread alone touches session_, always without the
  // lock; everything the UI thread reads or writes (below mutex_) is behind the lock. The loop
  // takes one command under the lock, carries it out unlocked, and publishes its results (the
  // snapshot, the scene, the figures) under the lock again.
  struct Command {
    enum class Kind { quit, restart, switch_method, snapshot, settle, advance } kind = Kind::quit;
    SceneConfig scene;        ///< restart
    std::string method;       ///< switch_method
    SnapshotWish wish;        ///< snapshot
    std::uint64_t steps = 0;  ///< advance
    double particles = 0.0;   ///< settle, advance: particles in the steps
  };
  void loop();
  /// Waits for work and takes it (lock held; runs an export job there, the UI waiting for it).
  Command take_command(std::unique_lock<std::mutex>& lock);
  /// The steps of the loop, each entered and left without the lock.
  void restart_session(SceneConfig scene);
  void switch_search(const std::string& name);
  void settle(double particles);
  void advance(std::uint64_t steps, double particles);
  /// The run stopped on an error: "stopped: ..." (lock not held).
  void stop(const std::exception& e);
  bool settle_progress();  // called by RunSession::settle between chunks (lock not held)
  /// Takes a snapshot with `wish` (lock not held) and hands it to the UI thread.
  void publish(const SnapshotWish& wish);
  /// The snapshot the next publish needs (lock not held): the wish as of now.
  SnapshotWish current_wish() const;
  void run_pending_job();  // (lock held)
  void note_team();        // copies the session's team into team_ (sim thread, lock held)

  SessionOptions options_;
  // The simulation thread's own (never read by the UI thread).
  std::unique_ptr<RunSession> session_;
  std::optional<ScheduledSwitch> scheduled_;
  std::uint64_t step_limit_ = 0;
  int threads_ = 1;
  std::uint64_t turn_start_ = 0;  ///< the session's steps when the settling ended

  mutable std::mutex mutex_;
  mutable std::condition_variable cv_;
  SceneConfig scene_;  ///< the session's scene, copied here whenever it changes (scene())
  std::shared_ptr<const FrameSnapshot> latest_;
  std::uint64_t generation_ = 0;
  mutable std::uint64_t taken_generation_ = 0;  ///< the newest snapshot latest() has handed out
  SnapshotWish wish_;
  bool running_ = false;
  bool step_once_ = false;
  bool quit_ = false;
  bool finished_ = false;
  bool settling_ = false;
  bool settled_ = false;
  bool snapshot_due_ = true;
  std::uint64_t settle_done_ = 0, settle_total_ = 0;
  std::uint64_t chunk_ = 10;
  std::optional<std::string> pending_method_;
  std::optional<SceneConfig> pending_restart_;
  std::function<void(const Simulation&)> pending_job_;
  std::string error_;
  double step_seconds_ = 0.0;
  double particle_steps_ = 0.0;
  std::optional<TeamChooser> team_;
  std::thread thread_;
};

}  // namespace drumlab::gui
