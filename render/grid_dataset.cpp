#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <vtkCellData.h>
#include <vtkImageData.h>
#include <vtkUnsignedIntArray.h>

#include "engine/search/cell_grid.hpp"
#include "render/vtk_datasets.hpp"

namespace drumlab::render {

vtkSmartPointer<vtkImageData> grid_dataset(const Simulation& sim, std::size_t max_cells) {
  const auto* grid = dynamic_cast<const CellGridSearch*>(&sim.search());
  if (grid == nullptr) return nullptr;
  const GridGeometry& g = grid->geometry();
  const double total =
      static_cast<double>(g.nx) * static_cast<double>(g.ny) * static_cast<double>(g.nz);
  if (g.nx <= 0 || total > static_cast<double>(max_cells)) {
    throw InputError(
        fmt::format("the {} grid has {:.3g} cells, more than the {} a grid dataset holds",
                    grid->name(), total, max_cells));
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetOrigin(g.origin.x(), g.origin.y(), g.origin.z());
  // A 2D grid spans the particles' z extent, which is 0 for a flat layer: give it a visible depth.
  image->SetSpacing(g.cell_xy, g.cell_xy, g.cell_z > 0.0 ? g.cell_z : g.cell_xy);
  image->SetDimensions(static_cast<int>(g.nx + 1), static_cast<int>(g.ny + 1),
                       static_cast<int>(g.nz + 1));
  vtkNew<vtkUnsignedIntArray> count;
  count->SetName("particles");
  count->SetNumberOfTuples(static_cast<vtkIdType>(total));
  count->FillValue(0);
  // Same binning as CellGridSearch::sort_into_cells (cell of each particle, clamped).
  for (const Vec3& x : sim.particles().position) {
    const Vec3 u = (x - g.origin) / g.cell_xy;
    const auto cx =
        std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(u.x())), 0, g.nx - 1);
    const auto cy =
        std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(u.y())), 0, g.ny - 1);
    std::int64_t cz = 0;
    if (g.nz > 1) {
      const double uz = (x.z() - g.origin.z()) / g.cell_z;
      cz = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(uz)), 0, g.nz - 1);
    }
    const auto cell = static_cast<vtkIdType>(cx + g.nx * (cy + g.ny * cz));
    count->SetValue(cell, count->GetValue(cell) + 1);
  }
  image->GetCellData()->AddArray(count);
  image->GetCellData()->SetActiveScalars("particles");
  return image;
}

}  // namespace drumlab::render
