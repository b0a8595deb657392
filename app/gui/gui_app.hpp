#pragma once
// The workbench window: GLFW (a real GLX context), Dear ImGui with its GLFW and OpenGL3 backends,
// and the VTK DrumView drawing into the window's default framebuffer through
// render::CurrentGlContext before ImGui draws its panels over it. The simulation runs in a
// SimThread; each frame shows its latest FrameSnapshot. Panels call only public setters of the
// SimThread and the DrumView.
#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "app/gui/gui_options.hpp"
#include "app/gui/sim_thread.hpp"
#include "app/gui/teach_steps.hpp"
#include "render/current_gl_context.hpp"
#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"

struct GLFWwindow;

namespace drumlab::gui {

/// The scene as the GUI runs it: the stability check (and so the settling's snapshots) at least
/// every 50 steps, so the settling shows as it happens. Checks are read-only: the trajectory is
/// the same as with the scene's own interval.
SceneConfig gui_scene(const std::string& file);
/// The same interval for a scene edited in the GUI.
SceneConfig with_gui_checks(SceneConfig scene);

/// A bounded series for a history plot.
struct History {
  std::deque<float> values;
  void add(double v, std::size_t keep = 300);
};

/// What --bench measured.
struct BenchFigures {
  double paused_fps = 0.0;          ///< frames/s drawn while paused, the camera orbiting
  double running_fps = 0.0;         ///< frames/s drawn while the simulation runs
  double gui_particle_steps = 0.0;  ///< particle-steps/s of the simulation inside the GUI
  double gui_steps = 0.0;           ///< particle-steps it made while running
};

class GuiApp {
 public:
  /// Opens the window and starts the simulation thread (paused unless headless). Throws
  /// InputError for bad input (before any window), std::runtime_error without a display.
  explicit GuiApp(const GuiOptions& options);
  ~GuiApp();
  GuiApp(const GuiApp&) = delete;
  GuiApp& operator=(const GuiApp&) = delete;

  /// Interactive: until the window closes. Headless (options.frames > 0): runs the frames, saves
  /// the screenshot and checkpoint if asked, and returns.
  void run();
  /// --bench: frames paused (orbiting) and running; returns the figures.
  BenchFigures bench(std::uint64_t frames);

 private:
  /// One UI frame: poll, panels, the view, ImGui over it; `grab` reads the window back first.
  void frame(const std::string& grab = {});
  void handle_mouse();
  void pick(double x, double y);
  void update_history(const FrameSnapshot& s);
  /// The snapshot as drawn (the teaching mode shows a prefix of the focus particle's search).
  FrameSnapshot display_snapshot(const FrameSnapshot& s);
  void push_view_options();
  /// The scene panel's scene as TOML (engine/scene/scene_writer.hpp; atomic).
  void save_edited_scene(const std::string& file);
  void push_wish();

  void panel_run();
  void panel_scene();
  void panel_search(const FrameSnapshot* s);
  void panel_view(const FrameSnapshot* s);
  void panel_export(const FrameSnapshot* s);
  void panel_teach(const FrameSnapshot* s);

  GuiOptions options_;
  GLFWwindow* window_ = nullptr;
  std::unique_ptr<render::CurrentGlContext> target_;
  std::unique_ptr<render::DrumView> view_;
  std::unique_ptr<SimThread> sim_;
  render::ViewOptions view_options_;
  std::shared_ptr<const FrameSnapshot> shown_;
  std::uint64_t shown_generation_ = 0;
  std::uint64_t drawn_generation_ = 0;  ///< the snapshot the view's scene was last updated from
  bool view_dirty_ = true;              ///< options changed since the last update

  // Scene editing.
  SceneConfig edited_;  ///< the scene file's scene with the panel's edits
  std::string scene_message_;
  std::string scene_path_ = "out/gui/edited_scene.toml";
  // Search.
  std::vector<std::string> methods_;
  int method_index_ = 0;
  // History plots.
  History cells_per_particle_, tests_per_particle_, contacts_per_particle_, kinetic_, step_ms_;
  std::uint64_t last_history_step_ = 0;
  StepTimers last_timers_;
  std::uint64_t last_timer_steps_ = 0;
  StepTimers recent_split_;
  // Mouse.
  bool dragging_ = false;
  double press_x_ = 0.0, press_y_ = 0.0, last_x_ = 0.0, last_y_ = 0.0;
  // Export.
  std::string png_path_ = "out/gui/view.png";
  std::string vtu_dir_ = "out/gui/vtu";
  std::string movie_path_ = "out/gui/movie.mp4";
  std::string export_message_;
  bool grab_view_ = false;
  std::unique_ptr<render::FrameWriter> movie_frames_;
  std::uint64_t movie_last_generation_ = 0;
  std::size_t vtu_frames_ = 0;
  // Teaching mode.
  bool teach_ = false;
  int teach_method_ = 0;      ///< index into teach_methods_
  int teach_step_ = 1 << 30;  ///< cells shown (clamped: the whole search until one steps)
  bool teach_play_ = false;
  bool teach_cycle_ = false;  ///< m1..m5 one after another
  double teach_last_advance_ = 0.0;
  std::vector<std::string> teach_methods_;
  std::optional<TeachWalk> walk_;
  std::uint64_t walk_generation_ = 0;
  int walk_method_ = -1;
  // Frame timing.
  double fps_ = 0.0;
  double last_frame_time_ = 0.0;
  double fps_since_ = 0.0;
  std::uint64_t frames_counted_ = 0;
};

}  // namespace drumlab::gui
