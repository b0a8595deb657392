#include "engine/io/paraview/wall_datasets.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace drumlab::paraview {

DataSet walls(std::span<const WallMesh> meshes, double drum_angle) {
  const double c = std::cos(drum_angle), s = std::sin(drum_angle);
  DataSet d;
  d.cells = CellKind::polygons;
  std::vector<std::uint32_t> mesh, patch;
  std::vector<std::uint8_t> attach;
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const WallMesh& w = meshes[k];
    const bool turns = w.attach == MeshAttach::drum;
    const auto first = static_cast<std::int64_t>(d.points.size());
    for (const Vec3& x : w.mesh.vertices) {
      d.points.push_back(turns ? Vec3(c * x.x() - s * x.y(), s * x.x() + c * x.y(), x.z()) : x);
    }
    for (std::size_t t = 0; t < w.mesh.size(); ++t) {
      const auto& v = w.mesh.triangles[t];
      d.add_cell({first + static_cast<std::int64_t>(v[0]), first + static_cast<std::int64_t>(v[1]),
                  first + static_cast<std::int64_t>(v[2])});
      mesh.push_back(static_cast<std::uint32_t>(k));
      patch.push_back(static_cast<std::uint32_t>(w.mesh.patch[t]));
      attach.push_back(turns ? 0 : 1);
    }
  }
  d.cell_data.push_back(make_array("mesh", std::move(mesh)));
  d.cell_data.push_back(make_array("patch", std::move(patch)));
  d.cell_data.push_back(make_array("attach", std::move(attach)));
  d.field_data.push_back(make_array("drum_angle", std::vector<double>{drum_angle}));
  d.active_scalars = "patch";
  return d;
}

DataSet walls(const Simulation& sim) {
  const auto meshes = sim.wall_meshes();
  if (!meshes) return walls(std::span<const WallMesh>{}, sim.drum_angle());
  return walls(*meshes, sim.drum_angle());
}

}  // namespace drumlab::paraview
