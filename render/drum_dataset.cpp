#include <cmath>
#include <numbers>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include "render/vtk_datasets.hpp"

namespace drumlab::render {
namespace {

void add_field(vtkPolyData* pd, const char* name, double value) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  pd->GetFieldData()->AddArray(a);
}

}  // namespace

vtkSmartPointer<vtkPolyData> drum_dataset(const Simulation& sim, int segments) {
  const DrumConfig& d = sim.scene().drum;
  const double r = 0.5 * d.diameter;
  const double h = d.depth;
  const double angle0 = sim.drum_angle();
  const bool caps = d.ends == DrumEnds::caps;
  // Points: ring k at z = 0 is 2k, at z = H is 2k + 1, starting at the drum angle.
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int k = 0; k < segments; ++k) {
    const double a = angle0 + 2.0 * std::numbers::pi * k / segments;
    points->InsertNextPoint(r * std::cos(a), r * std::sin(a), 0.0);
    points->InsertNextPoint(r * std::cos(a), r * std::sin(a), h);
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkUnsignedCharArray> part;
  part->SetName("part");
  vtkNew<vtkUnsignedCharArray> marker;
  marker->SetName("marker");
  const int stripe = std::max(1, segments / 24);
  for (int k = 0; k < segments; ++k) {
    const vtkIdType a = 2 * k;
    const vtkIdType b = 2 * ((k + 1) % segments);
    const vtkIdType quad[4] = {a, b, b + 1, a + 1};
    polys->InsertNextCell(4, quad);
    part->InsertNextValue(0);
    marker->InsertNextValue(k < stripe ? 1 : 0);
  }
  if (caps) {
    for (int cap = 0; cap < 2; ++cap) {
      std::vector<vtkIdType> ids(static_cast<std::size_t>(segments));
      for (int k = 0; k < segments; ++k) {
        // Outward normals: the low cap runs clockwise seen from +z, the high cap anticlockwise.
        const int kk = cap == 0 ? segments - 1 - k : k;
        ids[static_cast<std::size_t>(k)] = 2 * kk + cap;
      }
      polys->InsertNextCell(segments, ids.data());
      part->InsertNextValue(static_cast<unsigned char>(1 + cap));
      marker->InsertNextValue(0);
    }
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(part);
  pd->GetCellData()->AddArray(marker);
  add_field(pd, "drum_angle", sim.drum_angle());
  add_field(pd, "drum_omega", sim.drum_omega());
  return pd;
}

}  // namespace drumlab::render
