#pragma once
// The active cell grid drawn over the drum (viewed along its axis): cells coloured by occupancy,
// and one particle's search (ContactSearch::visit), for every method: its own cell, the forward
// half-shell cells it visits, the backward half it skips (its partners there find it), method 2's
// extra backward ring, a multi-level grid's cells in the smaller levels, the candidates it tests
// (a Verlet list: its listed pairs) and the contacts it finds; brute force has no cells, only a
// note. A 3D grid is shown as the layer of cells through the focus particle.
#include <optional>
#include <string>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include "engine/search/cell_grid.hpp"
#include "engine/session/frame_snapshot.hpp"
#include "render/palette.hpp"  // the focus picture's colours

class vtkActor;
class vtkRenderer;
class vtkPolyData;

namespace drumlab::render {

class GridOverlay {
 public:
  /// Cells are drawn by `renderer` (over the bed); the focus particle, its candidates and contacts
  /// by `top`, a layer above it, so particles nearer the camera never hide them.
  GridOverlay(vtkRenderer* renderer, vtkRenderer* top);
  ~GridOverlay();
  GridOverlay(const GridOverlay&) = delete;
  GridOverlay& operator=(const GridOverlay&) = delete;

  /// Redraws from the snapshot's search of the last step and its focus particle's visit (if it
  /// has one). Throws InputError if `occupancy` is asked for and the snapshot has no cell grid
  /// (FrameSnapshot::grid).
  void update(const FrameSnapshot& snapshot, bool occupancy);
  /// "focus id 12 (r = 15 mm): cells visited 41, pairs tested 63, contacts 4" (empty without one).
  const std::string& focus_summary() const { return summary_; }
  /// "grid 60 x 60 x 10, cell 15.0 mm\n  occupancy 1 (pale) .. 7 (blue)" (empty without --grid).
  const std::string& grid_summary() const { return grid_summary_; }
  /// Cells visited or skipped by the focus particle (for framing the camera).
  std::optional<Box> focus_box() const { return focus_box_; }
  /// The focus particle's replayed search in the last update.
  const std::optional<SearchVisit>& visit() const { return visit_; }

 private:
  /// Grid lines of `layer`, and its cells coloured by occupancy if `occupancy`.
  void draw_grid(const FrameSnapshot& s, const GridGeometry& g, std::int64_t layer, bool occupancy);
  void draw_focus(const FrameSnapshot& s, const SearchVisit& v, Index focus);
  /// The focus particle, its candidates and contacts as markers, and lines to the contacts.
  void draw_highlights(const FrameSnapshot& s, const SearchVisit& v, Index focus, double z);

  vtkRenderer* renderer_;
  vtkRenderer* top_;
  vtkSmartPointer<vtkActor> occupancy_, lines_, cells_, candidates_, own_, links_;
  std::string summary_;
  std::string grid_summary_;
  std::optional<Box> focus_box_;
  std::optional<SearchVisit> visit_;
};

}  // namespace drumlab::render
