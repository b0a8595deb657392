#include "render/vtk_datasets.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedIntArray.h>
#include <vtkUnstructuredGrid.h>

namespace drumlab::render {
namespace {

template <class Array, class T>
vtkSmartPointer<vtkAbstractArray> vtk_array(const paraview::DataArray& a,
                                            const std::vector<T>& values) {
  auto out = vtkSmartPointer<Array>::New();
  out->SetName(a.name.c_str());
  out->SetNumberOfComponents(a.components);
  out->SetNumberOfTuples(static_cast<vtkIdType>(a.tuples()));
  std::copy(values.begin(), values.end(), out->GetPointer(0));
  return out;
}

vtkSmartPointer<vtkAbstractArray> vtk_array(const paraview::DataArray& a) {
  struct Make {
    const paraview::DataArray& a;
    auto operator()(const std::vector<double>& v) { return vtk_array<vtkDoubleArray>(a, v); }
    auto operator()(const std::vector<std::uint32_t>& v) {
      return vtk_array<vtkUnsignedIntArray>(a, v);
    }
    auto operator()(const std::vector<std::uint8_t>& v) {
      return vtk_array<vtkUnsignedCharArray>(a, v);
    }
  };
  return std::visit(Make{a}, a.values);
}

void add_arrays(vtkFieldData* to, const std::vector<paraview::DataArray>& arrays) {
  for (const paraview::DataArray& a : arrays) to->AddArray(vtk_array(a));
}

void set_active(vtkDataSetAttributes* attributes, const paraview::DataSet& d) {
  if (!d.active_scalars.empty()) attributes->SetActiveScalars(d.active_scalars.c_str());
  if (!d.active_vectors.empty()) attributes->SetActiveVectors(d.active_vectors.c_str());
}

vtkSmartPointer<vtkCellArray> cell_array(const std::vector<std::int64_t>& connectivity,
                                         const std::vector<std::int64_t>& offsets) {
  vtkNew<vtkTypeInt64Array> points, ends;
  points->SetNumberOfTuples(static_cast<vtkIdType>(connectivity.size()));
  std::copy(connectivity.begin(), connectivity.end(), points->GetPointer(0));
  ends->SetNumberOfTuples(static_cast<vtkIdType>(offsets.size() + 1));
  ends->SetValue(0, 0);  // vtkCellArray's offsets start at 0
  std::copy(offsets.begin(), offsets.end(), ends->GetPointer(1));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(ends, points);
  return cells;
}

}  // namespace

vtkSmartPointer<vtkDataSet> to_vtk(const paraview::DataSet& d) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(d.points.size()));
  for (std::size_t i = 0; i < d.points.size(); ++i) {
    points->SetPoint(static_cast<vtkIdType>(i), d.points[i].data());
  }
  vtkSmartPointer<vtkDataSet> out;
  if (d.cells == paraview::CellKind::vertices) {
    const auto n = static_cast<vtkIdType>(d.points.size());
    auto cells = vtkSmartPointer<vtkCellArray>::New();
    cells->AllocateExact(n, n);
    for (vtkIdType k = 0; k < n; ++k) cells->InsertNextCell(1, &k);
    auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
    grid->SetPoints(points);
    grid->SetCells(VTK_VERTEX, cells);
    out = grid;
  } else {
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(points);
    const auto cells = cell_array(d.connectivity, d.offsets);
    if (d.cells == paraview::CellKind::lines) {
      poly->SetLines(cells);
    } else {
      poly->SetPolys(cells);
    }
    out = poly;
  }
  add_arrays(out->GetPointData(), d.point_data);
  add_arrays(out->GetCellData(), d.cell_data);
  add_arrays(out->GetFieldData(), d.field_data);
  set_active(d.cells == paraview::CellKind::vertices
                 ? static_cast<vtkDataSetAttributes*>(out->GetPointData())
                 : static_cast<vtkDataSetAttributes*>(out->GetCellData()),
             d);
  return out;
}

vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const Simulation& sim,
                                                       const GranuleCriterion& granule) {
  return vtkUnstructuredGrid::SafeDownCast(to_vtk(paraview::particles(sim, granule)));
}

vtkSmartPointer<vtkUnstructuredGrid> particles_dataset(const SeriesFrame& frame) {
  return vtkUnstructuredGrid::SafeDownCast(to_vtk(paraview::particles(frame)));
}

vtkSmartPointer<vtkPolyData> bonds_dataset(const SeriesFrame& frame) {
  return vtkPolyData::SafeDownCast(to_vtk(paraview::bonds(frame)));
}

vtkSmartPointer<vtkPolyData> drum_dataset(const Simulation& sim, int segments) {
  return vtkPolyData::SafeDownCast(to_vtk(paraview::drum(sim, segments)));
}

vtkSmartPointer<vtkPolyData> contacts_dataset(const Simulation& sim) {
  return vtkPolyData::SafeDownCast(to_vtk(paraview::contacts(sim)));
}

}  // namespace drumlab::render
