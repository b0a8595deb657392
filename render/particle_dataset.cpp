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

template <class Array>
vtkSmartPointer<Array> make_array(const char* name, int components, std::size_t n) {
  auto a = vtkSmartPointer<Array>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(static_cast<vtkIdType>(n));
  return a;
}

void set_vec(vtkDoubleArray* a, std::size_t i, const Vec3& v) {
  a->SetTypedTuple(static_cast<vtkIdType>(i), v.data());
}

}  // namespace

vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const Simulation& sim, double granule_age) {
  const Particles& p = sim.particles();
  const std::size_t n = p.size();
  std::vector<std::uint32_t> coordination;
  sim.coordination_numbers(coordination);

  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(static_cast<vtkIdType>(n), static_cast<vtkIdType>(n));
  auto id = make_array<vtkUnsignedIntArray>("id", 1, n);
  auto radius = make_array<vtkDoubleArray>("radius", 1, n);
  auto size_class = make_array<vtkUnsignedCharArray>("size_class", 1, n);
  auto velocity = make_array<vtkDoubleArray>("velocity", 3, n);
  auto speed = make_array<vtkDoubleArray>("speed", 1, n);
  auto omega = make_array<vtkDoubleArray>("angular_velocity", 3, n);
  auto force_array = make_array<vtkDoubleArray>("force", 3, n);
  auto coord = make_array<vtkUnsignedIntArray>("coordination", 1, n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<vtkIdType>(i);
    points->SetPoint(k, p.position[i].data());
    cells->InsertNextCell(1, &k);
    id->SetValue(k, p.id[i]);
    radius->SetValue(k, p.radius[i]);
    size_class->SetValue(k, p.size_class[i]);
    set_vec(velocity, i, p.velocity[i]);
    speed->SetValue(k, p.velocity[i].norm());
    set_vec(omega, i, p.omega[i]);
    set_vec(force_array, i, p.force[i]);
    coord->SetValue(k, coordination[i]);
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->SetCells(VTK_VERTEX, cells);
  vtkPointData* pd = grid->GetPointData();
  for (vtkAbstractArray* a :
       {static_cast<vtkAbstractArray*>(id), static_cast<vtkAbstractArray*>(radius),
        static_cast<vtkAbstractArray*>(size_class), static_cast<vtkAbstractArray*>(velocity),
        static_cast<vtkAbstractArray*>(speed), static_cast<vtkAbstractArray*>(omega),
        static_cast<vtkAbstractArray*>(force_array), static_cast<vtkAbstractArray*>(coord)}) {
    pd->AddArray(a);
  }
  if (scene_has_bonds(sim.scene())) {
    const std::vector<std::uint32_t> label = agglomerate_labels(sim, granule_age);
    const std::vector<double>* film = p.find_array(kLiquidFilmArray);
    auto agglomerate = make_array<vtkUnsignedIntArray>("agglomerate_id", 1, n);
    auto liquid = make_array<vtkDoubleArray>("liquid_volume", 1, n);
    for (std::size_t i = 0; i < n; ++i) {
      agglomerate->SetValue(static_cast<vtkIdType>(i), label[i]);
      liquid->SetValue(static_cast<vtkIdType>(i), film ? (*film)[i] : 0.0);
    }
    pd->AddArray(agglomerate);
    pd->AddArray(liquid);
  }
  pd->SetActiveScalars("radius");
  pd->SetActiveVectors("velocity");
  return grid;
}

}  // namespace drumlab::render
