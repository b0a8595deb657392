#include "render/drum_view.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <vtkActor.h>
#include <vtkActorCollection.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCoordinate.h>
#include <vtkCylinderSource.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkOpenGLSphereMapper.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegularPolygonSource.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkVariant.h>
#include <Eigen/Geometry>

#include "engine/io/paraview/frame_datasets.hpp"
#include "render/grid_overlay.hpp"
#include "render/vtk_datasets.hpp"
#include "render/wall_mesh_actors.hpp"

namespace drumlab::render {

namespace {

constexpr int kSpokes = 6;
/// Frames at least this high get the full overlay column; smaller ones two short lines.
constexpr int kFullOverlayHeight = 480;
/// Height / width above which a view counts as portrait (the legend goes below the disk).
constexpr double kPortrait = 1.15;

/// The continuous map: 256 colours of viridis, no categories.
void use_viridis(vtkLookupTable* lut) {
  lut->IndexedLookupOff();
  lut->ResetAnnotations();
  lut->SetNumberOfTableValues(256);
  for (int k = 0; k < 256; ++k) {
    const double x = 10.0 * k / 255.0;
    const int i = std::min(9, static_cast<int>(x));
    const double f = x - i;
    const double* a = kViridis[i];
    const double* b = kViridis[i + 1];
    lut->SetTableValue(k, a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]),
                       a[2] + f * (b[2] - a[2]), 1.0);
  }
}

/// One colour per category, looked up by value (the legend draws them as named swatches).
void use_categories(vtkLookupTable* lut, const std::vector<std::pair<double, std::string>>& cats,
                    bool first_grey) {
  lut->ResetAnnotations();
  lut->SetNumberOfTableValues(static_cast<vtkIdType>(cats.size()));
  for (std::size_t k = 0; k < cats.size(); ++k) {
    const double* c = first_grey ? (k == 0 ? kNeutralGrey : kCategories[k - 1]) : kCategories[k];
    lut->SetTableValue(static_cast<vtkIdType>(k), c[0], c[1], c[2], 1.0);
    lut->SetAnnotation(vtkVariant(cats[k].first), cats[k].second);
  }
  lut->IndexedLookupOn();
}

/// Lines: the rim circle at z and `kSpokes` spokes from the axis, in the drum's body frame.
vtkSmartPointer<vtkPolyData> cap_lines(double radius, double z) {
  auto pts = vtkSmartPointer<vtkPoints>::New();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  constexpr int kRim = 120;
  for (int k = 0; k < kRim; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kRim;
    pts->InsertNextPoint(radius * std::cos(a), radius * std::sin(a), z);
  }
  for (int k = 0; k < kRim; ++k) {
    const vtkIdType seg[2] = {k, (k + 1) % kRim};
    lines->InsertNextCell(2, seg);
  }
  const vtkIdType centre = pts->InsertNextPoint(0.0, 0.0, z);
  for (int k = 0; k < kSpokes; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kSpokes;
    const vtkIdType end = pts->InsertNextPoint(radius * std::cos(a), radius * std::sin(a), z);
    const vtkIdType seg[2] = {centre, end};
    lines->InsertNextCell(2, seg);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetLines(lines);
  return poly;
}

vtkSmartPointer<vtkActor> actor_for(vtkPolyData* poly) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// The overlay: a narrow column of short lines, to fit beside the drum.
std::string overlay_text(const FrameSnapshot& sim, const std::string& extra, bool compact) {
  const SearchCounters& c = sim.counters;
  const double n = std::max<double>(1.0, static_cast<double>(sim.size()));
  if (compact) {  // small frames: two lines in the bottom-left corner
    return fmt::format("t = {:.3f} s  rev {:.3f}\n{}: {:.1f} cells, {:.1f} tests / particle",
                       sim.time, sim.drum_angle / (2.0 * std::numbers::pi), sim.search_name,
                       static_cast<double>(c.cells_visited) / n,
                       static_cast<double>(c.pairs_tested) / n);
  }
  std::string what(sim.search_description);
  if (const auto colon = what.find(": "); colon != std::string::npos) what.erase(0, colon + 2);
  for (std::size_t k = what.find(", "); k != std::string::npos; k = what.find(", ", k)) {
    what.replace(k, 2, "\n  ");
  }
  std::string text = fmt::format(
      "t = {:.3f} s\nrevolutions {:.3f}\nstep {}\nN = {}\n\nsearch {}\n  {}\n\nlast step:\n"
      "cells visited {}\n  {:.1f} / particle\npairs tested {}\n  {:.1f} / particle\n"
      "pairs found {}",
      sim.time, sim.drum_angle / (2.0 * std::numbers::pi), sim.steps, sim.size(), sim.search_name,
      what, c.cells_visited, static_cast<double>(c.cells_visited) / n, c.pairs_tested,
      static_cast<double>(c.pairs_tested) / n, c.pairs_found);
  if (!extra.empty()) text += "\n\n" + extra;
  return text;
}

/// The grid's and the focus particle's lines of the overlay.
std::string grid_text(const GridOverlay& grid, bool focus) {
  std::string text = grid.grid_summary();
  if (focus && !grid.focus_summary().empty()) {
    if (!text.empty()) text += "\n\n";
    text += grid.focus_summary();
  }
  return text;
}

}  // namespace

FrameSnapshot view_snapshot(const Simulation& sim, const ViewOptions& options,
                            SnapshotRequest request) {
  // Storage indices change between frames (re-sorting); ids do not.
  if (options.focus_id) {
    index_of_id(sim.particles(), *options.focus_id);  // throws for an unknown id
    request.focus_id = options.focus_id;
  }
  FrameSnapshot s = take_snapshot(sim, request);
  s.color_values = particle_color_values(sim, options.color_by, options.granule);
  s.color_by = color_by_name(options.color_by);
  return s;
}

FrameSnapshot view_snapshot(const Simulation& sim, const ViewOptions& options) {
  SnapshotRequest request;
  request.diagnostics = false;
  return view_snapshot(sim, options, std::move(request));
}

CameraMode parse_camera(std::string_view s) {
  if (s == "axis") return CameraMode::axis;
  if (s == "iso") return CameraMode::iso;
  throw InputError(fmt::format("unknown camera '{}' (axis, iso)", s));
}

Index index_of_id(const Particles& p, Index id) {
  const auto it = std::find(p.id.begin(), p.id.end(), id);
  if (it == p.id.end()) {
    throw InputError(fmt::format("focus particle {} does not exist (N = {}, ids 0..{})", id,
                                 p.size(), p.size() - 1));
  }
  return static_cast<Index>(it - p.id.begin());
}

Index auto_focus_id(const Particles& p) {
  if (p.empty()) throw InputError("no particle to focus on: the scene has none");
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& x : p.position) centroid += x;
  centroid /= static_cast<double>(p.size());
  const double rmax = p.max_radius();
  std::size_t best = p.size();
  double best_d = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.radius[i] < rmax * (1.0 - 1e-9)) continue;
    const double d = (p.position[i] - centroid).squaredNorm();
    if (best == p.size() || d < best_d) {
      best = i;
      best_d = d;
    }
  }
  return p.id[best];
}

struct DrumView::Impl {
  Impl(const ViewOptions& o, RenderTarget& t) : options(o), target(t) {}
  void build_scene();
  void build_annotations();  // legend and text overlay, in the top layer
  /// A landscape or square view: the legend upright at the right edge; a portrait one (the
  /// workbench's view between its panel columns): across the bottom, below the drum's disk.
  void place_legend();
  void place_text();  // the overlay text's corner and font for the frame's height
  void build_drum(const FrameSnapshot& s);
  void update_particles(const FrameSnapshot& s);
  /// The airborne droplets as small blue points (a scene with [[spray]]).
  void update_droplets(const FrameSnapshot& s);
  void update_overlay(const FrameSnapshot& s);
  void place_camera();
  /// The picture's extent (x, y, z ranges): the drum, with the central axis above it (carrier
  /// frame) or the whole orbit (lab frame) for a planetary drum.
  std::array<double, 6> picture_bounds() const;
  void reset_clipping();
  void show_parts();  // the walls, legend and text toggles
  /// A planetary drum: the central axis and the arm (drum-frame points at this snapshot), and
  /// every 3D actor moved into the picture's frame (ViewOptions::frame).
  void update_carrier(const FrameSnapshot& s);
  Vec3 to_picture(const Vec3& x) const;    // drum frame -> the picture's frame
  Vec3 from_picture(const Vec3& y) const;  // and back
  bool compact_overlay() const { return options.height < kFullOverlayHeight; }

  ViewOptions options;
  RenderTarget& target;  // outlives the view: every VTK object below
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderer> top;  // layer 1: the focus particle's highlights, never hidden
  vtkNew<vtkPolyData> particles;
  vtkNew<vtkOpenGLSphereMapper> sphere_mapper;
  vtkNew<vtkActor> particle_actor;
  vtkNew<vtkLookupTable> lut;
  vtkNew<vtkScalarBarActor> legend;
  vtkNew<vtkTextActor> text;
  vtkSmartPointer<vtkActor> front_cap, back_cap, back_lines;  // the caps' lines turn with the drum
  vtkSmartPointer<vtkActor> mantle;
  vtkSmartPointer<vtkActor> nozzles;       // the [[spray]] nozzles' cones and fans (lines)
  std::unique_ptr<WallMeshActors> meshes;  // [[wall.mesh]], [[wall.lifters]]; none without
  vtkNew<vtkPolyData> droplets;
  vtkNew<vtkActor> droplet_actor;
  std::unique_ptr<GridOverlay> grid;
  vtkNew<vtkPolyData> arm_lines;  // the central axis and the arm ([drum.orbit])
  vtkSmartPointer<vtkActor> arm, central_axis;
  vtkNew<vtkTransform> picture;  // drum frame -> the picture's frame, on every 3D actor
  paraview::FrameMotion motion;  // the same motion
  double orbit_radius = 0.0;
  bool drum_built = false;
  bool camera_placed = false;
  bool focus_drawn = false;
  double drum_radius = 0.0, drum_depth = 0.0;  // of the drum built
};

void DrumView::Impl::build_scene() {
  window->SetOwnContext(false);
  window->SetSize(options.width, options.height);
  window->SetIsCurrent(true);
  window->SetReadyForRendering(true);
  window->SetMultiSamples(0);
  if (!window->InitializeFromCurrentContext()) {
    throw std::runtime_error("render: VTK could not use the target's OpenGL context");
  }
  window->AddRenderer(renderer);
  window->SetNumberOfLayers(2);  // layer 1: text, legend and the focus picture, always on top
  top->SetLayer(1);
  top->InteractiveOff();
  top->SetActiveCamera(renderer->GetActiveCamera());
  window->AddRenderer(top);
  renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);

  particles->SetPoints(vtkNew<vtkPoints>());
  sphere_mapper->SetInputData(particles);
  sphere_mapper->SetScaleArray("radius");
  sphere_mapper->SetLookupTable(lut);
  sphere_mapper->SetScalarModeToUsePointFieldData();
  sphere_mapper->SelectColorArray("color");
  sphere_mapper->ScalarVisibilityOn();
  sphere_mapper->SetColorModeToMapScalars();
  use_viridis(lut);
  particle_actor->SetMapper(sphere_mapper);
  particle_actor->GetProperty()->SetAmbient(0.15);
  particle_actor->GetProperty()->SetDiffuse(0.85);
  renderer->AddActor(particle_actor);

  build_annotations();
  if (options.grid || options.focus_id) grid = std::make_unique<GridOverlay>(renderer, top);
}

void DrumView::Impl::place_legend() {
  if (options.height > kPortrait * options.width) {
    legend->SetOrientationToHorizontal();
    legend->UnconstrainedFontSizeOn();  // the title at its font size, not stretched to the bar
    legend->SetPosition(0.1, 0.04);
    legend->SetWidth(0.8);
    legend->SetHeight(0.09);
  } else {
    legend->SetOrientationToVertical();
    legend->UnconstrainedFontSizeOff();
    legend->SetPosition(0.9, 0.1);
    legend->SetWidth(0.07);
    legend->SetHeight(0.8);
  }
}

void DrumView::Impl::build_annotations() {
  legend->SetLookupTable(lut);
  legend->SetNumberOfLabels(5);
  place_legend();
  legend->GetTitleTextProperty()->SetFontSize(14);
  legend->GetLabelTextProperty()->SetFontSize(12);
  text->GetTextProperty()->SetFontFamilyToCourier();
  text->GetTextProperty()->SetColor(0.95, 0.95, 0.95);
  place_text();
  if (options.overlay || !options.title.empty()) top->AddActor2D(text);
  if (options.overlay) top->AddActor2D(legend);
}

void DrumView::Impl::place_text() {
  const int font = options.height >= 600 ? 16 : 11;
  text->GetTextProperty()->SetFontSize(options.title.empty() ? font : 13);
  if (options.title.empty() && compact_overlay()) {
    text->SetDisplayPosition(6, 6);
    text->GetTextProperty()->SetVerticalJustificationToBottom();
  } else if (options.title.empty()) {
    text->SetDisplayPosition(12, options.height - 12);
    text->GetTextProperty()->SetVerticalJustificationToTop();
  } else {
    text->SetDisplayPosition(10, options.height - 10);
    text->GetTextProperty()->SetVerticalJustificationToTop();
    text->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
    text->GetTextProperty()->SetBackgroundOpacity(0.6);
  }
}

void DrumView::Impl::build_drum(const FrameSnapshot& s) {
  const double radius = s.drum_radius;
  const double depth = s.drum_depth;
  drum_radius = radius;
  drum_depth = depth;
  vtkNew<vtkCylinderSource> cylinder;  // along y: turn it onto z
  cylinder->SetRadius(radius);
  cylinder->SetHeight(depth);
  cylinder->SetResolution(96);
  cylinder->CappingOff();
  vtkNew<vtkTransform> to_z;
  to_z->Translate(0.0, 0.0, 0.5 * depth);
  to_z->RotateX(90.0);
  vtkNew<vtkTransformPolyDataFilter> mantle_tf;
  mantle_tf->SetInputConnection(cylinder->GetOutputPort());
  mantle_tf->SetTransform(to_z);
  mantle_tf->Update();
  mantle = actor_for(mantle_tf->GetOutput());
  mantle->GetProperty()->SetColor(0.7, 0.75, 0.85);
  mantle->GetProperty()->SetOpacity(0.12);
  renderer->AddActor(mantle);

  vtkNew<vtkRegularPolygonSource> disk;  // back cap, a dark plate behind the bed
  disk->SetNumberOfSides(120);
  disk->SetRadius(radius);
  disk->SetCenter(0.0, 0.0, -1e-4 * radius);
  disk->Update();
  back_cap = actor_for(disk->GetOutput());
  back_cap->GetProperty()->SetColor(kBackCapColor[0], kBackCapColor[1], kBackCapColor[2]);
  back_cap->GetProperty()->LightingOff();
  renderer->AddActor(back_cap);

  front_cap = actor_for(cap_lines(radius, depth));
  front_cap->GetProperty()->SetColor(0.85, 0.85, 0.6);
  front_cap->GetProperty()->SetLineWidth(2.0);
  front_cap->GetProperty()->SetOpacity(0.7);
  front_cap->GetProperty()->LightingOff();
  renderer->AddActor(front_cap);
  back_lines = actor_for(cap_lines(radius, 0.0));
  back_lines->GetProperty()->SetColor(0.45, 0.45, 0.35);
  back_lines->GetProperty()->LightingOff();
  renderer->AddActor(back_lines);
  if (!s.sprays.empty()) {
    const vtkSmartPointer<vtkDataSet> lines = to_vtk(paraview::nozzles(s.sprays, 2.0 * radius));
    nozzles = actor_for(vtkPolyData::SafeDownCast(lines));
    nozzles->GetMapper()->ScalarVisibilityOff();
    nozzles->GetProperty()->SetColor(0.3, 0.6, 1.0);
    nozzles->GetProperty()->SetLineWidth(1.5);
    nozzles->GetProperty()->LightingOff();
    renderer->AddActor(nozzles);
    droplets->SetPoints(vtkNew<vtkPoints>());
    droplets->SetVerts(vtkNew<vtkCellArray>());
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(droplets);
    droplet_actor->SetMapper(mapper);
    droplet_actor->GetProperty()->SetColor(0.55, 0.85, 1.0);
    droplet_actor->GetProperty()->SetPointSize(5.0);
    droplet_actor->GetProperty()->RenderPointsAsSpheresOn();
    renderer->AddActor(droplet_actor);
  }
  orbit_radius = s.orbit_radius;
  if (orbit_radius != 0.0) {
    arm = actor_for(arm_lines);
    arm->GetProperty()->SetColor(1.0, 0.6, 0.2);
    arm->GetProperty()->SetLineWidth(3.0);
    arm->GetProperty()->LightingOff();
    renderer->AddActor(arm);
    vtkNew<vtkRegularPolygonSource> hub;  // the central axis, seen end on: a small disk
    hub->SetNumberOfSides(24);
    hub->SetRadius(0.08 * radius);
    hub->Update();
    central_axis = actor_for(hub->GetOutput());
    central_axis->GetProperty()->SetColor(1.0, 0.6, 0.2);
    central_axis->GetProperty()->LightingOff();
    renderer->AddActor(central_axis);
  }
  drum_built = true;
}

void DrumView::Impl::update_carrier(const FrameSnapshot& s) {
  motion = picture_motion(s, options.frame);
  picture->Identity();
  picture->PostMultiply();
  picture->Translate(motion.offset.x(), motion.offset.y(), motion.offset.z());
  picture->RotateZ(motion.turn * 180.0 / std::numbers::pi);
  for (vtkRenderer* r : {renderer.Get(), top.Get()}) {
    vtkActorCollection* actors = r->GetActors();
    actors->InitTraversal();
    while (vtkActor* a = actors->GetNextActor()) a->SetUserTransform(picture);
  }
  if (!arm) return;
  // In the drum frame the central axis stands at -c; the arm joins it to the drum's axis.
  const Vec3 c = s.carrier_offset;
  const double h = s.drum_depth;
  vtkNew<vtkPoints> points;
  for (const Vec3& x : {Vec3(-c), Vec3(-c.x(), -c.y(), h), Vec3(Vec3::Zero()), Vec3(0.0, 0.0, h)}) {
    points->InsertNextPoint(x.x(), x.y(), x.z());
  }
  vtkNew<vtkCellArray> lines;
  for (const auto& [a, b] : {std::pair<vtkIdType, vtkIdType>{0, 1}, {0, 2}, {1, 3}}) {
    const vtkIdType ends[2] = {a, b};
    lines->InsertNextCell(2, ends);
  }
  central_axis->SetPosition(-c.x(), -c.y(), h);
  arm_lines->SetPoints(points);
  arm_lines->SetLines(lines);
  arm_lines->Modified();
}

Vec3 DrumView::Impl::to_picture(const Vec3& x) const {
  const Eigen::AngleAxisd turn(motion.turn, Vec3::UnitZ());
  return turn * (x + motion.offset);
}

Vec3 DrumView::Impl::from_picture(const Vec3& y) const {
  const Eigen::AngleAxisd turn(-motion.turn, Vec3::UnitZ());
  return turn * y - motion.offset;
}

paraview::FrameMotion picture_motion(const FrameSnapshot& s, paraview::ViewFrame frame) {
  paraview::FrameMotion m;
  if (s.orbit_radius == 0.0) return m;
  if (frame == paraview::ViewFrame::carrier) {
    m.turn = -0.5 * std::numbers::pi - s.carrier_angle;  // c, the field's direction, points down
  } else if (frame == paraview::ViewFrame::lab) {
    m.offset = s.carrier_offset;  // the central axis at the origin
  }
  return m;
}

void DrumView::Impl::update_droplets(const FrameSnapshot& s) {
  if (!nozzles) return;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  points->SetNumberOfPoints(static_cast<vtkIdType>(s.droplets.size()));
  for (std::size_t k = 0; k < s.droplets.size(); ++k) {
    const Vec3& x = s.droplets[k];
    points->SetPoint(static_cast<vtkIdType>(k), x.x(), x.y(), x.z());
    const vtkIdType id = static_cast<vtkIdType>(k);
    verts->InsertNextCell(1, &id);
  }
  droplets->SetPoints(points);
  droplets->SetVerts(verts);
  droplets->Modified();
}

void DrumView::Impl::update_particles(const FrameSnapshot& p) {
  if (p.color_values.size() != p.size()) {
    throw std::logic_error("DrumView: a snapshot without colour values (use view_snapshot)");
  }
  const ColorMap colors = color_map(p, parse_color_by(p.color_by));
  const auto n = static_cast<vtkIdType>(p.size());
  vtkPoints* pts = particles->GetPoints();
  pts->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> radius;
  radius->SetName("radius");
  radius->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> color;
  color->SetName("color");
  color->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i) {
    const Vec3& x = p.position[static_cast<std::size_t>(i)];
    pts->SetPoint(i, x.x(), x.y(), x.z());
    radius->SetValue(i, static_cast<float>(p.radius[static_cast<std::size_t>(i)]));
    color->SetValue(i, colors.values[static_cast<std::size_t>(i)]);
  }
  pts->Modified();
  if (particles->GetNumberOfVerts() != n) {
    vtkNew<vtkCellArray> verts;
    verts->AllocateExact(n, n);
    for (vtkIdType i = 0; i < n; ++i) verts->InsertNextCell(1, &i);
    particles->SetVerts(verts);
  }
  particles->GetPointData()->AddArray(radius);
  particles->GetPointData()->AddArray(color);
  particles->Modified();
  if (options.neutral_particles) {
    sphere_mapper->ScalarVisibilityOff();
    particle_actor->GetProperty()->SetColor(kNeutralGrey[0], kNeutralGrey[1], kNeutralGrey[2]);
  }
  if (colors.categories.empty()) {
    use_viridis(lut);
  } else {
    use_categories(lut, colors.categories, colors.first_grey);
  }
  lut->SetTableRange(colors.lo, colors.hi);
  sphere_mapper->SetScalarRange(colors.lo, colors.hi);
  legend->SetTitle(colors.title.c_str());
}

void DrumView::Impl::update_overlay(const FrameSnapshot& sim) {
  const double turn_deg = sim.drum_angle * 180.0 / std::numbers::pi;
  front_cap->SetOrientation(0.0, 0.0, turn_deg);
  back_lines->SetOrientation(0.0, 0.0, turn_deg);
  if (!options.title.empty()) {
    text->SetInput(options.title.c_str());
    return;
  }
  std::string extra = grid ? grid_text(*grid, focus_drawn) : "";
  if (sim.orbit_radius != 0.0 && !compact_overlay()) {
    const char* view = options.frame == paraview::ViewFrame::carrier ? "the arm's frame, field down"
                       : options.frame == paraview::ViewFrame::lab   ? "the lab frame"
                                                                     : "the drum's frame";
    if (!extra.empty()) extra += "\n\n";
    extra += fmt::format("carrier R_o = {:g} m\n  arm at {:.0f} deg\n  view: {}", sim.orbit_radius,
                         std::fmod(sim.carrier_angle * 180.0 / std::numbers::pi, 360.0), view);
  }
  text->SetInput(overlay_text(sim, extra, compact_overlay()).c_str());
}

void DrumView::Impl::show_parts() {
  for (vtkActor* a : {mantle.Get(), front_cap.Get(), back_cap.Get(), back_lines.Get(), arm.Get(),
                      central_axis.Get()}) {
    if (a != nullptr) a->SetVisibility(options.walls);
  }
  if (meshes) meshes->set_visibility(options.walls);
  legend->SetVisibility(options.legend);
  text->SetVisibility(options.text);
}

std::array<double, 6> DrumView::Impl::picture_bounds() const {
  const double r = drum_radius, d = drum_depth, ro = std::abs(orbit_radius);
  if (ro > 0.0 && options.frame == paraview::ViewFrame::carrier) {
    return {-r, r, -r, std::max(r, ro + 0.1 * r), -0.1 * d, 1.1 * d};  // the axis above the drum
  }
  if (ro > 0.0 && options.frame == paraview::ViewFrame::lab) {
    return {-(ro + r), ro + r, -(ro + r), ro + r, -0.1 * d, 1.1 * d};  // the whole orbit
  }
  return {-r, r, -r, r, -0.1 * d, 1.1 * d};
}

void DrumView::Impl::place_camera() {
  const double depth = drum_depth;
  const std::array<double, 6> b = picture_bounds();
  const double cx = 0.5 * (b[0] + b[1]), cy = 0.5 * (b[2] + b[3]);
  const double hx = 0.5 * (b[1] - b[0]), hy = 0.5 * (b[3] - b[2]);
  vtkCamera* cam = renderer->GetActiveCamera();
  const double far = 4.0 * (std::max(hx, hy) + depth);
  cam->SetFocalPoint(cx, cy, 0.5 * depth);
  cam->SetViewUp(0.0, 1.0, 0.0);
  if (options.camera == CameraMode::axis) {
    cam->ParallelProjectionOn();
    cam->SetPosition(cx, cy, 0.5 * depth + far);
    // The picture fits the frame: a portrait view of the drum is framed by its width.
    const double aspect = static_cast<double>(options.height) / options.width;
    cam->SetParallelScale(1.08 * std::max(hy, hx * aspect));
  } else {
    cam->ParallelProjectionOff();
    cam->SetPosition(cx + 0.9 * far, cy + 0.5 * far, 0.5 * depth + 1.4 * far);
    cam->SetViewAngle(30.0);
    renderer->ResetCamera(b[0], b[1], b[2], b[3], 0.0, depth);
    cam->Zoom(1.25);
  }
  if (options.zoom_to_focus && grid) {
    if (const auto box = grid->focus_box()) {
      const Vec3 c = to_picture(0.5 * (box->lo + box->hi));
      const double h = 0.5 * std::max(box->hi.y() - box->lo.y(),
                                      (box->hi.x() - box->lo.x()) * options.height / options.width);
      cam->SetFocalPoint(c.x(), c.y(), 0.5 * depth);
      cam->SetPosition(c.x(), c.y(), 0.5 * depth + far);
      cam->SetParallelScale(1.1 * h);
    }
  }
  reset_clipping();
  camera_placed = true;
}

void DrumView::Impl::reset_clipping() {
  const std::array<double, 6> b = picture_bounds();
  renderer->ResetCameraClippingRange(b[0], b[1], b[2], b[3], b[4], b[5]);
}

DrumView::DrumView(const ViewOptions& options, RenderTarget& target)
    : impl_(std::make_unique<Impl>(options, target)) {
  if (target.width() != options.width || target.height() != options.height) {
    throw std::runtime_error(fmt::format("render: a {}x{} view on a {}x{} target", options.width,
                                         options.height, target.width(), target.height()));
  }
  target.make_current();
  impl_->build_scene();
}

DrumView::~DrumView() {
  if (impl_) {
    impl_->target.make_current();
    impl_->window->Finalize();
  }
}

Image DrumView::render(const Simulation& sim) {
  return render(view_snapshot(sim, impl_->options));
}

Image DrumView::render(const FrameSnapshot& snapshot) {
  draw(snapshot);
  return impl_->target.read_image();
}

void DrumView::draw(const FrameSnapshot& snapshot) {
  Impl& m = *impl_;
  m.target.make_current();
  if (!m.drum_built) m.build_drum(snapshot);
  m.focus_drawn = snapshot.focus_visit.has_value();
  if (!m.grid && (m.options.grid || m.focus_drawn)) {
    m.grid = std::make_unique<GridOverlay>(m.renderer, m.top);
  }
  if (m.grid) m.grid->update(snapshot, m.options.grid);
  m.update_particles(snapshot);
  m.update_droplets(snapshot);
  if (snapshot.meshes && !m.meshes) m.meshes = std::make_unique<WallMeshActors>(m.renderer);
  if (m.meshes) m.meshes->update(snapshot);
  m.update_overlay(snapshot);
  m.update_carrier(snapshot);
  m.show_parts();
  if (!m.camera_placed) m.place_camera();
  m.window->Render();
}

std::array<double, 2> DrumView::project(const Vec3& x) {
  vtkNew<vtkCoordinate> c;
  c->SetCoordinateSystemToWorld();
  const Vec3 y = impl_->to_picture(x);
  c->SetValue(y.x(), y.y(), y.z());
  const double* d = c->GetComputedDoubleDisplayValue(impl_->renderer);
  return {d[0], static_cast<double>(impl_->options.height) - d[1]};
}

std::array<Vec3, 2> DrumView::sight_line(double x, double y) {
  vtkRenderer* r = impl_->renderer;
  std::array<Vec3, 2> ends;
  for (int k = 0; k < 2; ++k) {  // display depth 0: the near plane, 1: the far plane
    r->SetDisplayPoint(x, static_cast<double>(impl_->options.height) - y, k);
    r->DisplayToWorld();
    const double* w = r->GetWorldPoint();
    ends[static_cast<std::size_t>(k)] =
        impl_->from_picture(Vec3(w[0] / w[3], w[1] / w[3], w[2] / w[3]));
  }
  return ends;
}

std::optional<std::size_t> first_sphere_hit(const Vec3& near, const Vec3& far,
                                            std::span<const Vec3> centres,
                                            std::span<const double> radii) {
  const Vec3 d = (far - near).normalized();
  std::optional<std::size_t> best;
  double best_t = 0.0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    // |near + t d - c|^2 = r^2: t = b -+ sqrt(b^2 - (|near - c|^2 - r^2)), b = d.(c - near).
    const Vec3 m = centres[i] - near;
    const double b = d.dot(m);
    const double disc = b * b - (m.squaredNorm() - radii[i] * radii[i]);
    if (disc < 0.0) continue;
    const double t = b - std::sqrt(disc);  // where the line enters the sphere
    if (!best || t < best_t) {
      best = i;
      best_t = t;
    }
  }
  return best;
}

SearchVisit DrumView::focus_visit() const {
  if (!impl_->grid || !impl_->grid->visit()) {
    throw std::logic_error("DrumView::focus_visit: no focus particle drawn yet");
  }
  return *impl_->grid->visit();
}

void DrumView::redraw() {
  Impl& m = *impl_;
  if (!m.drum_built) throw std::logic_error("DrumView::redraw before the first frame");
  m.target.make_current();
  m.show_parts();
  if (!m.camera_placed) m.place_camera();
  m.window->Render();
}

void DrumView::set_options(const ViewOptions& options) {
  Impl& m = *impl_;
  if (options.title.empty() != m.options.title.empty() || options.overlay != m.options.overlay) {
    throw std::logic_error("DrumView::set_options: title and overlay are set at construction");
  }
  const bool camera_changed = options.camera != m.options.camera ||
                              options.zoom_to_focus != m.options.zoom_to_focus ||
                              options.frame != m.options.frame;
  const bool shade_changed = options.neutral_particles != m.options.neutral_particles;
  const int width = m.options.width, height = m.options.height;
  m.options = options;
  m.options.width = width;  // the size is set_size's
  m.options.height = height;
  if (camera_changed) m.camera_placed = false;
  if (shade_changed && !options.neutral_particles) {
    m.sphere_mapper->ScalarVisibilityOn();
  }
}

void DrumView::set_size(int width, int height) {
  Impl& m = *impl_;
  if (width == m.options.width && height == m.options.height) return;
  m.options.width = width;
  m.options.height = height;
  m.window->SetSize(width, height);
  m.place_text();
  m.place_legend();
}

const ViewOptions& DrumView::options() const {
  return impl_->options;
}

void DrumView::reset_camera() {
  impl_->camera_placed = false;
}

void DrumView::orbit(double azimuth_deg, double elevation_deg) {
  vtkCamera* cam = impl_->renderer->GetActiveCamera();
  cam->Azimuth(azimuth_deg);
  cam->Elevation(elevation_deg);
  cam->OrthogonalizeViewUp();
  impl_->reset_clipping();
}

void DrumView::zoom(double factor) {
  impl_->renderer->GetActiveCamera()->Zoom(factor);
  impl_->reset_clipping();
}

void DrumView::set_title(std::string title) {
  impl_->options.title = std::move(title);
}

std::array<double, 3> DrumView::legend_color(double value) const {
  std::array<double, 3> rgb{};
  impl_->lut->GetColor(value, rgb.data());
  return rgb;
}

}  // namespace drumlab::render
