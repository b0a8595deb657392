#pragma once
// The workbench: a GuiWindow (GLFW + Dear ImGui), the simulation in a SimThread, and the parts a
// frame shows: the MainView (VTK drawing into the window's image), the FocusInset, and the
// panels (Run and View here; Scene: SceneEditor, Search: SearchPanel, Export: ExportPanel,
// Teaching). Each frame shows the SimThread's latest FrameSnapshot; panels call only public
// setters of the SimThread, the views and the other parts.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "app/gui/export_panel.hpp"
#include "app/gui/focus_inset.hpp"
#include "app/gui/frame_clock.hpp"
#include "app/gui/frame_profile.hpp"
#include "app/gui/gui_bench.hpp"
#include "app/gui/gui_options.hpp"
#include "app/gui/gui_window.hpp"
#include "app/gui/main_view.hpp"
#include "app/gui/mouse_gesture.hpp"
#include "app/gui/scene_editor.hpp"
#include "app/gui/search_panel.hpp"
#include "app/gui/sim_thread.hpp"
#include "app/gui/teaching.hpp"

namespace drumlab::gui {

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
  /// simulation runs at most clock_.max_running_fps frames/s (the window need not draw faster
  /// than snapshots arrive; the rest of the CPU is the simulation's).
  void pace();
  /// Takes the SimThread's newest snapshot if there is one.
  void take_snapshot();
  /// The panels and the mouse (ImGui's frame).
  void panels();
  /// Renders the view and the inset of the shown snapshot, and what the Export panel takes;
  /// `t0`: the frame profile's clock.
  void render(bool full, double& t0);
  void handle_mouse();
  /// Focuses the front-most particle under window point (x, y); returns its id.
  std::optional<Index> pick(double x, double y);
  /// Headless: --orbit, --zoom and --pick, then one line about the view and the pick.
  void apply_view_flags();
  /// Headless --screenshot: where the view, the drum's disk and every panel lie in the window
  /// ("layout" lines, window units from the top left), for the layout test.
  void report_layout(const FrameSnapshot& s);
  /// Headless --pick: the pick and an independent check that it is the front-most particle.
  void report_pick(const FrameSnapshot& s, double x, double y);
  /// New view options: the view draws them and the snapshots carry what they need.
  void set_view_options(const render::ViewOptions& o);
  /// Tells the SimThread what the snapshots must carry (the view's focus, the teaching methods).
  void push_wish();
  FrameSnapshot drawn(const FrameSnapshot& s);

  void panel_run();
  void panel_view(const FrameSnapshot* s);
  /// The View panel's parts: each edits `o` and returns whether it changed.
  bool view_switches(render::ViewOptions& o, const FrameSnapshot* s);
  void camera_buttons(render::ViewOptions& o);
  void speed_fields();
  bool focus_fields(render::ViewOptions& o, const FrameSnapshot* s);

  GuiOptions options_;
  Teaching teaching_;
  std::unique_ptr<SimThread> sim_;
  std::optional<SceneEditor> scene_editor_;
  std::optional<SearchPanel> search_;
  ExportPanel export_;
  std::unique_ptr<GuiWindow> window_;  // the GL objects below are released before it
  std::unique_ptr<MainView> view_;
  std::unique_ptr<FocusInset> inset_;
  MouseGesture mouse_;
  FrameClock clock_;
  FrameProfile profile_;
  bool profiling_ = false;
  std::shared_ptr<const FrameSnapshot> shown_;
  std::uint64_t shown_generation_ = 0;
};

}  // namespace drumlab::gui
