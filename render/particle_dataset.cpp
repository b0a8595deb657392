#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedIntArray.h>
#include <vtkUnstructuredGrid.h>

#include "engine/analysis/agglomerates.hpp"
#include "render/vtk_datasets.hpp"

namespace drumlab::render {
namespace {

template <class Array, class T>
vtkSmartPointer<Array> make_array(const char* name, std::span<const T> values) {
  auto a = vtkSmartPointer<Array>::New();
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), values[i]);
  return a;
}

vtkSmartPointer<vtkDoubleArray> make_vectors(const char* name, std::span<const Vec3> values) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    a->SetTypedTuple(static_cast<vtkIdType>(i), values[i].data());
  }
  return a;
}

}  // namespace

vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const ParticleFields& f) {
  const std::size_t n = f.position.size();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(static_cast<vtkIdType>(n), static_cast<vtkIdType>(n));
  std::vector<double> speed(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<vtkIdType>(i);
    points->SetPoint(k, f.position[i].data());
    cells->InsertNextCell(1, &k);
    speed[i] = f.velocity[i].norm();
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->SetCells(VTK_VERTEX, cells);
  vtkPointData* pd = grid->GetPointData();
  pd->AddArray(make_array<vtkUnsignedIntArray>("id", f.id));
  pd->AddArray(make_array<vtkDoubleArray>("radius", f.radius));
  pd->AddArray(make_array<vtkUnsignedCharArray>("size_class", f.size_class));
  pd->AddArray(make_vectors("velocity", f.velocity));
  pd->AddArray(make_array<vtkDoubleArray>("speed", std::span<const double>(speed)));
  pd->AddArray(make_vectors("angular_velocity", f.omega));
  if (!f.force.empty()) pd->AddArray(make_vectors("force", f.force));
  if (!f.coordination.empty()) {
    pd->AddArray(make_array<vtkUnsignedIntArray>("coordination", f.coordination));
  }
  if (!f.agglomerate_id.empty()) {
    pd->AddArray(make_array<vtkUnsignedIntArray>("agglomerate_id", f.agglomerate_id));
    pd->AddArray(make_array<vtkDoubleArray>("liquid_volume", f.liquid_volume));
  }
  pd->SetActiveScalars("radius");
  pd->SetActiveVectors("velocity");
  return grid;
}

vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const Simulation& sim, double granule_age) {
  const Particles& p = sim.particles();
  std::vector<std::uint32_t> coordination;
  sim.coordination_numbers(coordination);
  ParticleFields f;
  f.position = p.position;
  f.velocity = p.velocity;
  f.omega = p.omega;
  f.force = p.force;
  f.radius = p.radius;
  f.id = p.id;
  f.size_class = p.size_class;
  f.coordination = coordination;
  std::vector<std::uint32_t> label;
  std::vector<double> liquid;
  if (scene_has_bonds(sim.scene())) {
    label = agglomerate_labels(sim, granule_age);
    const std::vector<double>* film = p.find_array(kLiquidFilmArray);
    liquid = film ? *film : std::vector<double>(p.size(), 0.0);
    f.agglomerate_id = label;
    f.liquid_volume = liquid;
  }
  return particles_dataset(f);
}

vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const SeriesFrame& frame) {
  ParticleFields f;
  f.position = frame.position;
  f.velocity = frame.velocity;
  f.omega = frame.omega;
  f.radius = frame.radius;
  f.id = frame.id;
  f.size_class = frame.size_class;
  f.agglomerate_id = frame.agglomerate_id;
  f.liquid_volume = frame.film;
  return particles_dataset(f);
}

}  // namespace drumlab::render
