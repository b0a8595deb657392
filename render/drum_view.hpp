#pragma once
// The drum as a picture: particles as shaded sphere impostors coloured by one quantity with a
// legend, the drum mantle and end caps (with spokes that turn with the drum), the triangle walls
// (lifters, inserts: turning with the drum or standing in the lab), a text overlay, and
// optionally the active search grid and one particle's search. Reads a const Simulation; draws
// into an OpenGL context it is given (a RenderTarget: OSMesa for the CLI and the tests, the GUI's
// own context). No VTK type appears in this interface.
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/io/paraview/view_frame.hpp"
#include "engine/search/cell_grid.hpp"
#include "engine/session/frame_snapshot.hpp"
#include "engine/simulation.hpp"
#include "render/image.hpp"
#include "render/palette.hpp"
#include "render/particle_colors.hpp"
#include "render/render_target.hpp"

namespace drumlab::render {

enum class CameraMode { axis, iso };

/// Parses "axis" or "iso"; throws InputError otherwise.
CameraMode parse_camera(std::string_view s);

struct ViewOptions;
/// The snapshot a view with `options` draws: take_snapshot(sim, request) with the options' focus
/// particle, plus the colour values of options.color_by. Throws InputError for an unknown focus
/// id. Without a request: no diagnostics, no compared methods.
FrameSnapshot view_snapshot(const Simulation& sim, const ViewOptions& options,
                            SnapshotRequest request);
FrameSnapshot view_snapshot(const Simulation& sim, const ViewOptions& options);

struct ViewOptions {
  int width = 1280;
  int height = 720;
  ColorBy color_by = ColorBy::size;
  GranuleCriterion granule;  ///< criterion of ColorBy::agglomerate (granule_options), s
  CameraMode camera = CameraMode::axis;
  bool grid = false;               ///< colour the active grid's cells by occupancy
  std::optional<Index> focus_id;   ///< stable id of the particle whose search is shown
  bool zoom_to_focus = false;      ///< frame the focus particle's stencil instead of the drum
  bool neutral_particles = false;  ///< grey particles, so the focus picture's colours stand out
  bool overlay = true;             ///< text overlay and legend
  bool walls = true;               ///< the mantle, the end caps and the triangle walls
  bool legend = true;              ///< with overlay: the legend
  bool text = true;                ///< with overlay: the text
  std::string title;               ///< replaces the overlay text when not empty
  /// A planetary drum ([drum.orbit]) is drawn in this frame, with the central axis and the arm:
  /// carrier (default): turning with the arm, the drum's centre still, the arm pointing up from
  /// it to the central axis and the carrier's field pointing down, so a steady bed looks steady;
  /// lab: the central axis still at the centre of the picture, the drum orbiting it; drum: the
  /// engine's frame (the drum's centre still, not turning). A drum without an orbit is always
  /// drawn in its own frame.
  paraview::ViewFrame frame = paraview::ViewFrame::carrier;
};

/// The rigid motion (x -> R(turn) (x + offset), about z) from the drum frame into the picture's
/// frame for a snapshot: identity without an orbit or for `drum` (see ViewOptions::frame).
paraview::FrameMotion picture_motion(const FrameSnapshot& snapshot, paraview::ViewFrame frame);

class DrumView {
 public:
  /// Draws into `target` (which must outlive the view, and be options.width x options.height).
  /// Throws std::runtime_error if VTK cannot use the target's context.
  DrumView(const ViewOptions& options, RenderTarget& target);
  ~DrumView();
  DrumView(const DrumView&) = delete;
  DrumView& operator=(const DrumView&) = delete;

  /// Updates the scene from `sim` and renders one frame (making the target's context current):
  /// render(view_snapshot(sim, options())).
  Image render(const Simulation& sim);
  /// Renders one frame of a snapshot (view_snapshot: it carries its colour values; its focus
  /// visit, if any, is drawn) and reads it back.
  Image render(const FrameSnapshot& snapshot);
  /// As render(snapshot), without reading the frame back (a window shows it itself).
  void draw(const FrameSnapshot& snapshot);
  /// Draws the last frame's scene again (a new camera, the walls/legend/text toggles), without
  /// reading a snapshot: a paused window turning its camera. Throws before the first frame.
  void redraw();
  /// Changes what the next frames show (colour-by, grid, focus, camera preset, zoom to focus,
  /// neutral particles). The size (set_size), the title and the overlay stay as they are.
  void set_options(const ViewOptions& options);
  /// Draws the next frames at width x height pixels (the target must be of that size by then): a
  /// resized window, or a reduced image while the camera moves. The camera keeps its view.
  void set_size(int width, int height);
  const ViewOptions& options() const;
  /// Places the camera by the preset again at the next frame (and frames the focus if
  /// zoom_to_focus).
  void reset_camera();
  /// Turns the camera about the focal point (degrees) / moves it closer (factor > 1).
  void orbit(double azimuth_deg, double elevation_deg);
  void zoom(double factor);
  /// Pixel (column, row from the top) where a drum-frame point appears in the last frame.
  std::array<double, 2> project(const Vec3& x);
  /// The line of sight through pixel (column x, row y from the top) of the last frame: its points
  /// on the near and the far clipping plane, in the drum frame (picking: first_sphere_hit).
  std::array<Vec3, 2> sight_line(double x, double y);
  /// The focus particle's search as drawn in the last frame (ContactSearch::visit). Throws
  /// std::logic_error without a focus particle or before the first frame.
  SearchVisit focus_visit() const;
  /// Replaces the title text (ViewOptions::title) for the next frame.
  void set_title(std::string title);
  /// The colour the legend assigns to `value` (RGB in [0, 1]), for tests.
  std::array<double, 3> legend_color(double value) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Of the spheres (centres, radii) that the line of sight from `near` to `far` passes through, the
/// one it enters first (the front-most under a cursor); none if it meets none.
std::optional<std::size_t> first_sphere_hit(const Vec3& near, const Vec3& far,
                                            std::span<const Vec3> centres,
                                            std::span<const double> radii);

/// Storage index of the particle with stable id `id`; throws InputError if there is none.
Index index_of_id(const Particles& p, Index id);
/// A particle worth showing: the largest particle nearest to the centroid of the bed (stable id).
Index auto_focus_id(const Particles& p);

}  // namespace drumlab::render
