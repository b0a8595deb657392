#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedIntArray.h>

#include <unordered_map>

#include "engine/analysis/agglomerates.hpp"
#include "engine/drum.hpp"
#include "engine/periodic.hpp"
#include "render/vtk_datasets.hpp"

namespace drumlab::render {

vtkSmartPointer<vtkPolyData> contacts_dataset(const Simulation& sim) {
  std::vector<ContactForce> contacts;
  sim.contact_forces(contacts);
  const bool wet = scene_has_bonds(sim.scene());
  std::vector<Bond> bonds;
  sim.bonds(bonds);
  // Each bond on its contact's line, or on a line of its own (force 0) where the spheres part.
  const auto key = [](Index i, Index j) { return (std::uint64_t{i} << 32) | j; };
  std::unordered_map<std::uint64_t, std::size_t> line_of;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    line_of.emplace(key(contacts[k].i, contacts[k].j), k);
  }
  std::vector<std::size_t> bond_line(bonds.size());
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const auto at = line_of.find(key(bonds[b].i, bonds[b].j));
    if (at != line_of.end()) {
      bond_line[b] = at->second;
    } else {
      bond_line[b] = contacts.size();
      contacts.push_back({bonds[b].i, bonds[b].j, Vec3::Zero()});
    }
  }
  const Particles& p = sim.particles();
  const double period = Drum(sim.scene().drum).period();
  const auto m = static_cast<vtkIdType>(contacts.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(2 * m);
  vtkNew<vtkCellArray> lines;
  lines->AllocateExact(m, 2 * m);
  vtkNew<vtkDoubleArray> magnitude;
  magnitude->SetName("force_magnitude");
  magnitude->SetNumberOfTuples(m);
  vtkNew<vtkDoubleArray> force;
  force->SetName("force");
  force->SetNumberOfComponents(3);
  force->SetNumberOfTuples(m);
  vtkNew<vtkUnsignedIntArray> id_a;
  id_a->SetName("id_a");
  id_a->SetNumberOfTuples(m);
  vtkNew<vtkUnsignedIntArray> id_b;
  id_b->SetName("id_b");
  id_b->SetNumberOfTuples(m);
  for (vtkIdType k = 0; k < m; ++k) {
    const ContactForce& c = contacts[static_cast<std::size_t>(k)];
    const Vec3 d = nearest_image(p.position[c.i], p.position[c.j], period);
    const Vec3 other = p.position[c.i] - d;  // partner's image nearest to i
    points->SetPoint(2 * k, p.position[c.i].data());
    points->SetPoint(2 * k + 1, other.data());
    const vtkIdType ends[2] = {2 * k, 2 * k + 1};
    lines->InsertNextCell(2, ends);
    magnitude->SetValue(k, c.force.norm());
    force->SetTypedTuple(k, c.force.data());
    id_a->SetValue(k, p.id[c.i]);
    id_b->SetValue(k, p.id[c.j]);
  }
  vtkNew<vtkDoubleArray> bridge_volume;
  bridge_volume->SetName("bridge_volume");
  bridge_volume->SetNumberOfTuples(m);
  bridge_volume->Fill(0.0);
  vtkNew<vtkDoubleArray> bridge_force;
  bridge_force->SetName("bridge_force");
  bridge_force->SetNumberOfTuples(m);
  bridge_force->Fill(0.0);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const auto k = static_cast<vtkIdType>(bond_line[b]);
    bridge_volume->SetValue(k, bonds[b].volume);
    bridge_force->SetValue(k, bonds[b].force);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetLines(lines);
  pd->GetCellData()->AddArray(magnitude);
  pd->GetCellData()->AddArray(force);
  pd->GetCellData()->AddArray(id_a);
  pd->GetCellData()->AddArray(id_b);
  if (wet) {
    pd->GetCellData()->AddArray(bridge_volume);
    pd->GetCellData()->AddArray(bridge_force);
  }
  pd->GetCellData()->SetActiveScalars("force_magnitude");
  return pd;
}

}  // namespace drumlab::render
