#pragma once
// The workbench's main view: the VTK DrumView rendering into the window's ViewImage through
// render::CurrentGlContext, what it shows (render::ViewOptions), its camera, and when it renders:
// only when something changed (a new snapshot, the options, the camera, the size), at a reduced
// size while it moves (ImageReduction).
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>

#include "app/gui/gui_window.hpp"
#include "app/gui/image_reduction.hpp"
#include "app/gui/view_image.hpp"
#include "render/current_gl_context.hpp"
#include "render/drum_view.hpp"

namespace drumlab::gui {

class MainView {
 public:
  /// The view of `window` (its GL context current), sized to its view area (GuiWindow::view_area).
  MainView(const GuiWindow& window, render::ViewOptions options);
  ~MainView();
  MainView(const MainView&) = delete;
  MainView& operator=(const MainView&) = delete;

  const render::ViewOptions& options() const { return options_; }
  /// What the view shows (the next render draws the scene again).
  void set_options(const render::ViewOptions& options);
  const ImageReduction& reduction() const { return reduction_; }
  void set_reduction(const ImageReduction& r) { reduction_ = r; }

  /// The camera moved (orbit, zoom) or is to be placed by its preset again (`reset`).
  void camera_changed(bool reset = false);
  void orbit(double azimuth_deg, double elevation_deg);
  void zoom(double factor);
  /// Places the camera by its preset and counts it as still (full size at once).
  void place_camera();
  /// The camera preset (axis, iso), placed anew.
  void set_camera_mode(render::CameraMode mode);
  /// Moved within the last quarter second (the view is rendered reduced meanwhile).
  bool moving() const;
  /// The camera moved since the view last rendered.
  bool camera_dirty() const { return camera_dirty_; }
  /// Nothing to render: the camera still, the image at full size (the scene aside).
  bool still() const;

  /// The window's framebuffer changed size: the view takes its new view area.
  void set_window_size(int width, int height);
  /// Where the view lies in the window's framebuffer: x, width (pixels; every row).
  GuiWindow::ViewArea area() const { return {area_x_, fb_w_}; }

  /// What render() did: the reduction factor it rendered at (0: nothing rendered) and whether it
  /// drew the scene anew (not only the camera).
  struct Rendered {
    int factor = 0;
    bool scene = false;
  };
  /// Renders the view into its image if something changed: `generation` names the snapshot `s`,
  /// `teach_key` the teaching walk's method and step (drawn anew when it changes while
  /// `teaching`), `drawn` gives the snapshot as drawn. `full`: at full size even while moving.
  Rendered render(const FrameSnapshot& s, std::uint64_t generation, std::pair<int, int> teach_key,
                  bool teaching, bool full, bool running,
                  const std::function<FrameSnapshot(const FrameSnapshot&)>& drawn);
  /// The snapshot generation drawn last.
  std::uint64_t drawn_generation() const { return drawn_generation_; }
  /// Clears the window's framebuffer and draws the image into the view area.
  void show() const;
  /// Adapts the automatic reduction to the time the last frame took.
  void adapt_reduction(double seconds);
  /// The image as rendered last (for a PNG or a movie frame).
  render::Image read_image();
  /// The front-most particle of `s` under window point (x, y) in window units (the window
  /// `window_w` x `window_h` units): its id.
  std::optional<Index> pick(const FrameSnapshot& s, double x, double y,
                            std::array<int, 2> window_size);
  /// Window point (x, y) in the image's pixels (outside [0, width) left or right of the view).
  std::array<double, 2> image_pixel(double x, double y, std::array<int, 2> window_size) const;
  /// The VTK view itself (projections and sight lines for the headless checks).
  render::DrumView& drum_view() { return *view_; }

 private:
  const GuiWindow& window_;
  render::ViewOptions options_;
  ViewImage image_;  ///< what the view rendered last (shown again while nothing changed)
  std::unique_ptr<render::CurrentGlContext> target_;  ///< binds image_
  std::unique_ptr<render::DrumView> view_;
  ImageReduction reduction_;
  int fb_w_ = 0, fb_h_ = 0;  ///< the view area's size, pixels
  int area_x_ = 0;           ///< its left edge in the framebuffer, pixels
  int window_w_ = 0;         ///< the framebuffer's width, pixels
  double camera_moved_at_ = -1e9;
  bool camera_dirty_ = true;
  bool options_dirty_ = true;                ///< options changed since the last draw
  std::uint64_t drawn_generation_ = 0;       ///< the snapshot the view's scene was last drawn from
  std::pair<int, int> drawn_teach_{-1, -1};  ///< teaching method and step last drawn
};

}  // namespace drumlab::gui
