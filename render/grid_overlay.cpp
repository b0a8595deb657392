#include "render/grid_overlay.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkOpenGLSphereMapper.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include "engine/search/search_methods.hpp"

namespace drumlab::render {

namespace {

/// Quads in the plane z, one per cell, each with an RGBA colour.
struct QuadBuilder {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkUnsignedCharArray> colors;
  QuadBuilder() { colors->SetNumberOfComponents(4); }

  void add(const GridGeometry& g, std::int64_t cx, std::int64_t cy, double z, const double* rgb,
           double alpha) {
    const double x0 = g.origin.x() + static_cast<double>(cx) * g.cell_xy;
    const double y0 = g.origin.y() + static_cast<double>(cy) * g.cell_xy;
    const double x1 = x0 + g.cell_xy, y1 = y0 + g.cell_xy;
    const vtkIdType ids[4] = {
        points->InsertNextPoint(x0, y0, z), points->InsertNextPoint(x1, y0, z),
        points->InsertNextPoint(x1, y1, z), points->InsertNextPoint(x0, y1, z)};
    polys->InsertNextCell(4, ids);
    const auto byte = [](double v) {
      return static_cast<unsigned char>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5);
    };
    colors->InsertNextTuple4(byte(rgb[0]), byte(rgb[1]), byte(rgb[2]), byte(alpha));
  }
  vtkSmartPointer<vtkPolyData> poly() {
    auto p = vtkSmartPointer<vtkPolyData>::New();
    p->SetPoints(points);
    p->SetPolys(polys);
    p->GetCellData()->SetScalars(colors);
    return p;
  }
};

vtkSmartPointer<vtkActor> direct_color_actor(vtkPolyData* poly) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  mapper->SetColorModeToDirectScalars();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  return actor;
}

/// Highlighted particles are drawn as markers of this share of their radius, so the bed and the
/// cells under them stay visible.
constexpr double kMarkerScale = 0.6;

/// Front plane of the drum, where the grid is drawn (slightly in front of every particle).
double front_z(const FrameSnapshot& s) {
  return s.drum_depth * 1.02 + 1e-4;
}

void append_sphere(vtkPoints* pts, vtkFloatArray* radius, vtkUnsignedCharArray* colors,
                   const Vec3& x, double r, const double* rgb) {
  pts->InsertNextPoint(x.x(), x.y(), x.z());
  radius->InsertNextValue(static_cast<float>(r));
  colors->InsertNextTuple3(rgb[0] * 255.0, rgb[1] * 255.0, rgb[2] * 255.0);
}

/// The outline of one cell, drawn thick in the top layer.
vtkSmartPointer<vtkActor> own_cell_outline(const GridGeometry& g, const CellCoord& c, double z) {
  vtkNew<vtkPoints> pts;
  const double x0 = g.origin.x() + static_cast<double>(c.x) * g.cell_xy;
  const double y0 = g.origin.y() + static_cast<double>(c.y) * g.cell_xy;
  pts->InsertNextPoint(x0, y0, z);
  pts->InsertNextPoint(x0 + g.cell_xy, y0, z);
  pts->InsertNextPoint(x0 + g.cell_xy, y0 + g.cell_xy, z);
  pts->InsertNextPoint(x0, y0 + g.cell_xy, z);
  vtkNew<vtkCellArray> loop;
  const vtkIdType ids[5] = {0, 1, 2, 3, 0};
  loop->InsertNextCell(5, ids);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  poly->SetLines(loop);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(kOwnCellColor[0], kOwnCellColor[1], kOwnCellColor[2]);
  actor->GetProperty()->SetLineWidth(3.0);
  actor->GetProperty()->LightingOff();
  return actor;
}

}  // namespace

GridOverlay::GridOverlay(vtkRenderer* renderer, vtkRenderer* top)
    : renderer_(renderer), top_(top) {}

GridOverlay::~GridOverlay() {
  for (vtkActor* a : {occupancy_.Get(), lines_.Get(), cells_.Get(), candidates_.Get(), own_.Get(),
                      links_.Get()}) {
    if (a != nullptr) {
      renderer_->RemoveActor(a);
      top_->RemoveActor(a);
    }
  }
}

void GridOverlay::update(const FrameSnapshot& s, bool occupancy) {
  if (occupancy && !s.grid) {
    throw InputError(fmt::format("search '{}' has no cell grid to draw (methods with one: {})",
                                 s.search_name, fmt::join(cell_grid_method_names(), ", ")));
  }
  for (vtkActor* a : {occupancy_.Get(), lines_.Get(), cells_.Get(), candidates_.Get(), own_.Get(),
                      links_.Get()}) {
    if (a != nullptr) {
      renderer_->RemoveActor(a);
      top_->RemoveActor(a);
    }
  }
  summary_.clear();
  grid_summary_.clear();
  focus_box_.reset();
  visit_.reset();
  if (s.grid && s.grid->nx == 0) return;  // no search yet
  const std::optional<Index> focus = s.focus_visit ? s.focus_index : std::nullopt;
  const std::optional<SearchVisit>& v = s.focus_visit;
  // The grid whose lines are drawn: the cell grid, else the focus particle's own level.
  std::optional<GridGeometry> drawn;
  if (s.grid) {
    drawn = *s.grid;
  } else if (v && !v->grids.empty()) {
    drawn = v->grids.front().geometry;
  }
  // A Verlet list's structure is its listed partners: its builder's grid only when its
  // occupancy is asked for.
  if (s.lists_pairs && !occupancy) drawn.reset();
  if (drawn) {
    std::int64_t layer = drawn->nz / 2;
    if (focus) {
      layer = (v && !v->grids.empty() && v->grids.front().has_own)
                  ? v->grids.front().own.z
                  : cell_containing(*drawn, s.position[*focus]).z;
    }
    draw_grid(s, *drawn, layer, occupancy);
  }
  if (focus) draw_focus(s, *v, *focus);
}

void GridOverlay::draw_grid(const FrameSnapshot& s, const GridGeometry& g, std::int64_t layer,
                            bool occupancy) {
  std::map<std::pair<std::int64_t, std::int64_t>, int> count;
  int most = 1;
  for (const Vec3& x : s.position) {
    const CellCoord c = cell_containing(g, x);
    if (c.z != layer) continue;
    most = std::max(most, ++count[{c.x, c.y}]);
  }
  if (occupancy) {
    grid_summary_ = fmt::format(
        "grid {} x {} x {}, cell {:.1f} mm\n  occupancy 1 (pale) .. {} (blue){}", g.nx, g.ny, g.nz,
        1000.0 * g.cell_xy, most, g.nz > 1 ? fmt::format("\n  layer {} shown", layer) : "");
  }
  const double z = front_z(s);
  QuadBuilder quads;
  for (const auto& [cell, n] : count) {
    if (!occupancy) break;
    const double t = static_cast<double>(n) / most;
    const double rgb[3] = {0.95 - 0.85 * t, 0.95 - 0.6 * t, 0.6 + 0.35 * t};
    quads.add(g, cell.first, cell.second, z, rgb, 0.35 + 0.3 * t);
  }
  occupancy_ = direct_color_actor(quads.poly());
  renderer_->AddActor(occupancy_);

  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> lines;
  const double x0 = g.origin.x(), y0 = g.origin.y();
  const double x1 = x0 + g.nx * g.cell_xy, y1 = y0 + g.ny * g.cell_xy;
  for (std::int64_t k = 0; k <= g.nx; ++k) {
    const double x = x0 + k * g.cell_xy;
    const vtkIdType seg[2] = {pts->InsertNextPoint(x, y0, z), pts->InsertNextPoint(x, y1, z)};
    lines->InsertNextCell(2, seg);
  }
  for (std::int64_t k = 0; k <= g.ny; ++k) {
    const double y = y0 + k * g.cell_xy;
    const vtkIdType seg[2] = {pts->InsertNextPoint(x0, y, z), pts->InsertNextPoint(x1, y, z)};
    lines->InsertNextCell(2, seg);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  poly->SetLines(lines);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  lines_ = vtkSmartPointer<vtkActor>::New();
  lines_->SetMapper(mapper);
  lines_->GetProperty()->SetColor(0.6, 0.6, 0.65);
  lines_->GetProperty()->SetOpacity(0.35);
  lines_->GetProperty()->LightingOff();
  renderer_->AddActor(lines_);
}

namespace {

/// The focus particle's cells as quads in the plane z, and the box that frames them.
struct FocusCells {
  QuadBuilder quads;
  Box box{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  bool boxed = false;

  void add(const GridGeometry& g, const CellCoord& c, double z, const double* rgb, double alpha) {
    quads.add(g, c.x, c.y, z, rgb, alpha);
    const Vec3 lo = g.origin + Vec3(c.x * g.cell_xy, c.y * g.cell_xy, 0.0);
    box.lo = box.lo.cwiseMin(lo);
    box.hi = box.hi.cwiseMax(lo + Vec3(g.cell_xy, g.cell_xy, 0.0));
    boxed = true;
  }

  /// The levels without the particle's own cell (finer cells, drawn below), in its layer.
  void add_smaller_levels(const SearchVisit& v, const Vec3& x, double z) {
    for (const VisitedCells& cells : v.grids) {
      if (cells.has_own) continue;
      const std::int64_t layer = cell_containing(cells.geometry, x).z;
      for (const CellCoord& c : cells.forward) {
        if (c.z == layer) add(cells.geometry, c, z, kSmallerLevelColor, 0.35);
      }
    }
  }

  /// The grid with the particle's own cell: forward cells, the mirrored cells a half stencil
  /// skips, the backward ring and the own cell, in its layer. Returns that grid (or nullptr).
  const VisitedCells* add_own_grid(const SearchVisit& v, double z) {
    const auto own = std::find_if(v.grids.begin(), v.grids.end(),
                                  [](const VisitedCells& c) { return c.has_own; });
    if (own == v.grids.end()) return nullptr;
    const GridGeometry& g = own->geometry;
    const CellCoord& o = own->own;
    auto in_grid = [&g](const CellCoord& c) {
      return c.x >= 0 && c.x < g.nx && c.y >= 0 && c.y < g.ny;
    };
    for (const CellCoord& c : own->forward) {
      if (c.z != o.z) continue;
      add(g, c, z, kForwardCellColor, 0.5);
      const CellCoord m{2 * o.x - c.x, 2 * o.y - c.y, o.z};  // the mirrored, skipped cell
      if (in_grid(m) &&
          std::find(own->backward.begin(), own->backward.end(), m) == own->backward.end()) {
        add(g, m, z, kSkippedCellColor, 0.4);
      }
    }
    for (const CellCoord& c : own->backward) {
      if (c.z == o.z) add(g, c, z, kBackwardRingColor, 0.5);
    }
    add(g, o, z, kOwnCellColor, 0.7);
    return &*own;
  }

  /// No cells (a Verlet list): frame the listed partners and the particle.
  void frame_partners(const FrameSnapshot& p, const SearchVisit& v, Index focus) {
    for (Index j : v.candidates) {
      box.lo = box.lo.cwiseMin(p.position[j] - Vec3::Constant(p.radius[j]));
      box.hi = box.hi.cwiseMax(p.position[j] + Vec3::Constant(p.radius[j]));
    }
    box.lo = box.lo.cwiseMin(p.position[focus] - Vec3::Constant(2.0 * p.radius[focus]));
    box.hi = box.hi.cwiseMax(p.position[focus] + Vec3::Constant(2.0 * p.radius[focus]));
    boxed = true;
  }
};

/// The lines the view shows about the focus particle's search.
std::string describe_focus(const FrameSnapshot& p, const SearchVisit& v, Index focus,
                           const VisitedCells* own) {
  const std::string head =
      fmt::format("focus id {} (r = {:.0f} mm)", p.id[focus], 1000.0 * p.radius[focus]);
  switch (v.kind) {
    case SearchVisit::Kind::cells: {
      const GridGeometry& g = v.grids.front().geometry;
      return fmt::format(
          "{}\n  cells visited {}\n  pairs tested {}\n  contacts {}{}", head, v.cells_visited,
          v.pairs_tested, v.contacts.size(),
          g.nz > 1 ? fmt::format("\n  3D grid: layer {} of {}", v.grids.front().own.z, g.nz) : "");
    }
    case SearchVisit::Kind::levels:
      return fmt::format("{}\n  {}\n  cells visited {}\n  pairs tested {}\n  contacts {}{}", head,
                         own != nullptr ? own->label : "", v.cells_visited, v.pairs_tested,
                         v.contacts.size(), v.grids.size() > 1 ? "\n  violet: smaller levels" : "");
    case SearchVisit::Kind::list:
      return fmt::format("{}\n  Verlet list\n  listed partners {}\n  contacts {}", head,
                         v.candidates.size(), v.contacts.size());
    case SearchVisit::Kind::all:
      break;
  }
  return fmt::format(
      "{}\n  brute force: no cells\n  tests all N-1 = {}\n  ({} by itself)\n  contacts {}", head,
      p.size() - 1, v.pairs_tested, v.contacts.size());
}

}  // namespace

void GridOverlay::draw_focus(const FrameSnapshot& p, const SearchVisit& v, Index focus) {
  const double z = front_z(p) + 1e-4;
  FocusCells cells;
  const VisitedCells* own = nullptr;
  if (v.kind != SearchVisit::Kind::list) {  // a list's partners are drawn, not its builder's cells
    cells.add_smaller_levels(v, p.position[focus], z);
    own = cells.add_own_grid(v, z);
  }
  cells_ = direct_color_actor(cells.quads.poly());
  renderer_->AddActor(cells_);
  if (own != nullptr) {
    own_ = own_cell_outline(own->geometry, own->own, z);
    top_->AddActor(own_);
  }
  draw_highlights(p, v, focus, z);
  if (!cells.boxed && v.kind == SearchVisit::Kind::list) cells.frame_partners(p, v, focus);
  summary_ = describe_focus(p, v, focus, own);
  if (cells.boxed) focus_box_ = cells.box;
  visit_ = v;
}

void GridOverlay::draw_highlights(const FrameSnapshot& p, const SearchVisit& v, Index focus,
                                  double z) {
  vtkNew<vtkPolyData> spheres;
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> radius;
  radius->SetName("radius");
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetNumberOfComponents(3);
  append_sphere(pts, radius, colors, p.position[focus], p.radius[focus] * kMarkerScale,
                kFocusParticleColor);
  vtkNew<vtkPoints> link_pts;
  vtkNew<vtkCellArray> links;
  // Brute force tests everyone: its candidates would cover the bed; only its contacts are drawn.
  const std::vector<Index>& shown = v.kind == SearchVisit::Kind::all ? v.contacts : v.candidates;
  for (Index j : shown) {
    const bool contact = std::find(v.contacts.begin(), v.contacts.end(), j) != v.contacts.end();
    append_sphere(pts, radius, colors, p.position[j],
                  p.radius[j] * (contact ? kMarkerScale : 0.75 * kMarkerScale),
                  contact ? kContactColor : kCandidateColor);
    if (contact) {
      const Vec3& a = p.position[focus];
      const Vec3& b = p.position[j];
      const vtkIdType seg[2] = {link_pts->InsertNextPoint(a.x(), a.y(), z),
                                link_pts->InsertNextPoint(b.x(), b.y(), z)};
      links->InsertNextCell(2, seg);
    }
  }
  vtkNew<vtkCellArray> verts;  // the sphere mapper draws vertex cells
  for (vtkIdType k = 0; k < pts->GetNumberOfPoints(); ++k) verts->InsertNextCell(1, &k);
  spheres->SetPoints(pts);
  spheres->SetVerts(verts);
  spheres->GetPointData()->AddArray(radius);
  spheres->GetPointData()->SetScalars(colors);
  vtkNew<vtkOpenGLSphereMapper> mapper;
  mapper->SetInputData(spheres);
  mapper->SetScaleArray("radius");
  mapper->SetColorModeToDirectScalars();
  candidates_ = vtkSmartPointer<vtkActor>::New();
  candidates_->SetMapper(mapper);
  top_->AddActor(candidates_);

  vtkNew<vtkPolyData> link_poly;
  link_poly->SetPoints(link_pts);
  link_poly->SetLines(links);
  vtkNew<vtkPolyDataMapper> link_mapper;
  link_mapper->SetInputData(link_poly);
  links_ = vtkSmartPointer<vtkActor>::New();
  links_->SetMapper(link_mapper);
  links_->GetProperty()->SetColor(kContactColor[0], kContactColor[1], kContactColor[2]);
  links_->GetProperty()->SetLineWidth(3.0);
  links_->GetProperty()->LightingOff();
  top_->AddActor(links_);
}

}  // namespace drumlab::render
