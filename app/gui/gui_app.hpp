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
#include "app/gui/view_image.hpp"
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

/// Seconds on a steady clock.
double now_seconds();
/// The session options of the GUI's flags (scene, method, settle time).
SessionOptions session_options(const GuiOptions& o);

/// A bounded series for a history plot.
struct History {
  std::deque<float> values;
  void add(double v, std::size_t keep = 300);
};

/// Where the UI thread's time goes, summed over frames (with glFinish between the parts, so the
/// GL work is charged to the part that issued it; only while measuring).
struct FrameProfile {
  double panels = 0.0;  ///< ImGui's panels built (CPU)
  double view = 0.0;    ///< the VTK view rendered into its image (when something changed)
  double inset = 0.0;   ///< the focus inset rendered
  double show = 0.0;    ///< the view's image blitted into the window
  double imgui = 0.0;   ///< ImGui drawn over it
  double swap = 0.0;    ///< buffers swapped
  double wait = 0.0;    ///< paced: waiting for the next frame (running) or events
  std::uint64_t frames = 0;
  std::uint64_t renders = 0;  ///< frames that rendered the view (the others showed the last image)
  std::uint64_t reduction_sum = 0;  ///< the reduction factors of those renders, summed
};

/// What --bench measured.
struct BenchFigures {
  double paused_fps = 0.0;               ///< frames/s drawn while paused, the camera orbiting
  double still_fps = 0.0;                ///< frames/s paused, the camera still, full size
  double running_fps = 0.0;              ///< frames/s drawn while the simulation runs
  double running_pictures = 0.0;         ///< of those, new snapshots rendered per second
  double gui_particle_steps = 0.0;       ///< particle-steps/s of the simulation inside the GUI
  double gui_wall_particle_steps = 0.0;  ///< particle-steps per wall second while running
  double gui_steps = 0.0;                ///< particle-steps it made while running
  FrameProfile orbiting, still, running;
  double max_running_fps = 0.0;  ///< the pacing while the simulation runs
};

/// The CLI-equivalent run of the GUI's scene: one RunSession, one thread, no window, `steps`
/// turning steps after the settling; particle-steps per second.
double cli_particle_steps(const GuiOptions& options, std::uint64_t steps);
/// Prints --bench's figures.
void print_bench(const GuiOptions& options, const BenchFigures& b, std::uint64_t frames, double cli,
                 std::uint64_t cli_steps);

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
  /// Waits before a frame: for events while nothing changes (interactive), and while the
  /// simulation runs at most max_running_fps_ frames/s (the window need not draw faster than
  /// snapshots arrive; the rest of the CPU is the simulation's).
  void pace();
  /// Renders the view into image_ if something changed (a new snapshot, options, the camera, the
  /// size); at 1 / reduction_ of the size while the camera moves unless `full`.
  void render_view(const FrameSnapshot& s, bool full);
  void render_inset(const FrameSnapshot& s);
  /// The image reduction factor for this frame (1: full size).
  int reduction_now(bool full) const;
  /// Adapts the automatic factor to the time a reduced frame took.
  void adapt_reduction(int used, double seconds);
  void panel_inset();
  /// The camera moved (orbit, zoom) or is to be placed by its preset again (`reset`).
  void camera_changed(bool reset = false);
  /// Places the next ImGui window (x, y < 0: from the right / bottom edge).
  void place(float x, float y, float w) const;
  void handle_mouse();
  /// Focuses the front-most particle under window pixel (x, y); returns its id.
  std::optional<Index> pick(double x, double y);
  /// Headless: --orbit, --zoom and --pick, then one line about the view and the pick.
  void apply_view_flags();
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
  ViewImage image_;  ///< what the view rendered last (shown again while nothing changed)
  std::unique_ptr<render::CurrentGlContext> target_;  ///< binds image_
  std::unique_ptr<render::DrumView> view_;
  // The focus inset: a second view of the same snapshot framing the focus particle's search.
  ViewImage inset_image_;
  std::unique_ptr<render::CurrentGlContext> inset_target_;
  std::unique_ptr<render::DrumView> inset_;
  bool inset_on_ = true;
  int inset_size_ = 360;
  std::uint64_t inset_generation_ = 0;
  bool inset_dirty_ = true;
  // Rendering policy.
  int fb_w_ = 0, fb_h_ = 0;     ///< the window's framebuffer size
  bool relayout_ = false;       ///< the window changed size: place the panels again
  int reduction_ = 2;           ///< image reduction factor while the view moves (1: none)
  bool auto_reduction_ = true;  ///< adapt the factor to 30 frames/s instead (2..4)
  int adaptive_reduction_ = 2;
  bool reduce_running_ = true;  ///< the view counts as moving while the simulation runs
  float max_running_fps_ = 15;  ///< frames/s at most while the simulation runs
  double camera_moved_at_ = -1e9;
  bool camera_dirty_ = true;
  std::pair<int, int> drawn_teach_{-1, -1};  ///< teaching method and step last rendered
  FrameProfile profile_;
  bool profiling_ = false;
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
