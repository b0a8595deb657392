#include "render/grid_overlay.hpp"

#include <algorithm>
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
double front_z(const Simulation& sim) {
  return sim.scene().drum.depth * 1.02 + 1e-4;
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

void GridOverlay::update(const Simulation& sim, bool occupancy, std::optional<Index> focus) {
  const auto* grid = dynamic_cast<const CellGridSearch*>(&sim.search());
  if (grid == nullptr) {
    throw InputError(fmt::format("search '{}' has no cell grid to draw (methods with one: {})",
                                 sim.search().name(), fmt::join(cell_grid_method_names(), ", ")));
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
  trace_.reset();
  if (grid->geometry().nx == 0) return;  // no search yet
  std::int64_t layer = grid->geometry().nz / 2;
  if (focus) layer = grid->cell_of(*focus).z;
  draw_grid(sim, *grid, layer, occupancy);
  if (focus) draw_focus(sim, *grid, *focus);
}

void GridOverlay::draw_grid(const Simulation& sim, const CellGridSearch& grid, std::int64_t layer,
                            bool occupancy) {
  const GridGeometry& g = grid.geometry();
  std::map<std::pair<std::int64_t, std::int64_t>, int> count;
  int most = 1;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {
    const CellCoord& c = grid.cell_of(static_cast<Index>(i));
    if (c.z != layer) continue;
    most = std::max(most, ++count[{c.x, c.y}]);
  }
  if (occupancy) {
    grid_summary_ = fmt::format(
        "grid {} x {} x {}, cell {:.1f} mm\n  occupancy 1 (pale) .. {} (blue){}", g.nx, g.ny, g.nz,
        1000.0 * g.cell_xy, most, g.nz > 1 ? fmt::format("\n  layer {} shown", layer) : "");
  }
  const double z = front_z(sim);
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

void GridOverlay::draw_focus(const Simulation& sim, const CellGridSearch& grid, Index focus) {
  const GridGeometry& g = grid.geometry();
  const SearchTrace t = grid.trace(focus);
  const double z = front_z(sim) + 1e-4;
  auto in_grid = [&g](const CellCoord& c) {
    return c.x >= 0 && c.x < g.nx && c.y >= 0 && c.y < g.ny;
  };
  auto same_as = [](const CellCoord& c) { return [c](const CellCoord& d) { return c == d; }; };
  QuadBuilder quads;
  Box box{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  auto add_cell = [&](const CellCoord& c, const double* rgb, double alpha) {
    quads.add(g, c.x, c.y, z, rgb, alpha);
    const Vec3 lo = g.origin + Vec3(c.x * g.cell_xy, c.y * g.cell_xy, 0.0);
    box.lo = box.lo.cwiseMin(lo);
    box.hi = box.hi.cwiseMax(lo + Vec3(g.cell_xy, g.cell_xy, 0.0));
  };
  for (const CellCoord& c : t.forward) {
    if (c.z != t.own.z) continue;
    add_cell(c, kForwardCellColor, 0.5);
    const CellCoord m{2 * t.own.x - c.x, 2 * t.own.y - c.y, t.own.z};  // the mirrored, skipped cell
    if (in_grid(m) && std::none_of(t.backward.begin(), t.backward.end(), same_as(m))) {
      add_cell(m, kSkippedCellColor, 0.4);
    }
  }
  for (const CellCoord& c : t.backward) {
    if (c.z == t.own.z) add_cell(c, kBackwardRingColor, 0.5);
  }
  add_cell(t.own, kOwnCellColor, 0.7);
  cells_ = direct_color_actor(quads.poly());
  renderer_->AddActor(cells_);
  own_ = own_cell_outline(g, t.own, z);
  top_->AddActor(own_);
  draw_highlights(sim, t, focus, z);

  const Particles& p = sim.particles();
  summary_ = fmt::format(
      "focus id {} (r = {:.0f} mm)\n  cells visited {}\n  pairs tested {}\n  contacts {}{}",
      p.id[focus], 1000.0 * p.radius[focus], t.cells_visited(), t.candidates.size(),
      t.contacts.size(), g.nz > 1 ? fmt::format("\n  3D grid: layer {} of {}", t.own.z, g.nz) : "");
  focus_box_ = box;
  trace_ = t;
}

void GridOverlay::draw_highlights(const Simulation& sim, const SearchTrace& t, Index focus,
                                  double z) {
  const Particles& p = sim.particles();
  vtkNew<vtkPolyData> spheres;
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> radius;
  radius->SetName("radius");
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetNumberOfComponents(3);
  const double white[3] = {1.0, 1.0, 1.0};
  append_sphere(pts, radius, colors, p.position[focus], p.radius[focus] * kMarkerScale, white);
  vtkNew<vtkPoints> link_pts;
  vtkNew<vtkCellArray> links;
  for (Index j : t.candidates) {
    const bool contact = std::find(t.contacts.begin(), t.contacts.end(), j) != t.contacts.end();
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
