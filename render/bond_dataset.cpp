#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedIntArray.h>

#include "engine/periodic.hpp"
#include "render/vtk_datasets.hpp"

namespace drumlab::render {
namespace {

template <class Array>
vtkSmartPointer<Array> cell_array(const char* name, vtkIdType n) {
  auto a = vtkSmartPointer<Array>::New();
  a->SetName(name);
  a->SetNumberOfTuples(n);
  return a;
}

}  // namespace

vtkSmartPointer<vtkPolyData> bonds_dataset(const SeriesFrame& frame) {
  const auto m = static_cast<vtkIdType>(frame.bonds.size());
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(2 * m);
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  lines->AllocateExact(m, 2 * m);
  auto volume = cell_array<vtkDoubleArray>("bridge_volume", m);
  auto force = cell_array<vtkDoubleArray>("bridge_force", m);
  auto age = cell_array<vtkDoubleArray>("age", m);
  auto id_a = cell_array<vtkUnsignedIntArray>("id_a", m);
  auto id_b = cell_array<vtkUnsignedIntArray>("id_b", m);
  for (vtkIdType k = 0; k < m; ++k) {
    const Bond& b = frame.bonds[static_cast<std::size_t>(k)];
    const Vec3& a = frame.position[b.i];
    const Vec3 other = a - nearest_image(a, frame.position[b.j], frame.period);
    points->SetPoint(2 * k, a.data());
    points->SetPoint(2 * k + 1, other.data());
    const vtkIdType ends[2] = {2 * k, 2 * k + 1};
    lines->InsertNextCell(2, ends);
    volume->SetValue(k, b.volume);
    force->SetValue(k, b.force);
    age->SetValue(k, b.age);
    id_a->SetValue(k, frame.id[b.i]);
    id_b->SetValue(k, frame.id[b.j]);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetLines(lines);
  for (vtkAbstractArray* a :
       {static_cast<vtkAbstractArray*>(volume), static_cast<vtkAbstractArray*>(force),
        static_cast<vtkAbstractArray*>(age), static_cast<vtkAbstractArray*>(id_a),
        static_cast<vtkAbstractArray*>(id_b)}) {
    pd->GetCellData()->AddArray(a);
  }
  pd->GetCellData()->SetActiveScalars("bridge_force");
  return pd;
}

}  // namespace drumlab::render
