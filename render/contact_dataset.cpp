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

namespace {

/// The line of each bond: its contact's, or a line of its own (force 0, appended to `contacts`)
/// where the spheres have parted.
std::vector<std::size_t> bond_lines(const std::vector<Bond>& bonds,
                                    std::vector<ContactForce>& contacts) {
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
  return bond_line;
}

template <class Array>
vtkSmartPointer<Array> named_array(const char* name, vtkIdType tuples, int components = 1) {
  auto a = vtkSmartPointer<Array>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  return a;
}

/// One line per contact, from i to the image of j nearest to it, with the force and both ids.
vtkSmartPointer<vtkPolyData> contact_lines(const Simulation& sim,
                                           const std::vector<ContactForce>& contacts) {
  const Particles& p = sim.particles();
  const double period = Drum(sim.scene().drum).period();
  const auto m = static_cast<vtkIdType>(contacts.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(2 * m);
  vtkNew<vtkCellArray> lines;
  lines->AllocateExact(m, 2 * m);
  auto magnitude = named_array<vtkDoubleArray>("force_magnitude", m);
  auto force = named_array<vtkDoubleArray>("force", m, 3);
  auto id_a = named_array<vtkUnsignedIntArray>("id_a", m);
  auto id_b = named_array<vtkUnsignedIntArray>("id_b", m);
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
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetLines(lines);
  pd->GetCellData()->AddArray(magnitude);
  pd->GetCellData()->AddArray(force);
  pd->GetCellData()->AddArray(id_a);
  pd->GetCellData()->AddArray(id_b);
  return pd;
}

}  // namespace

vtkSmartPointer<vtkPolyData> contacts_dataset(const Simulation& sim) {
  std::vector<ContactForce> contacts;
  sim.contact_forces(contacts);
  std::vector<Bond> bonds;
  sim.bonds(bonds);
  const std::vector<std::size_t> bond_line = bond_lines(bonds, contacts);
  auto pd = contact_lines(sim, contacts);
  if (scene_has_bonds(sim.scene())) {  // each bond's volume and force on its line, 0 elsewhere
    const auto m = static_cast<vtkIdType>(contacts.size());
    auto bridge_volume = named_array<vtkDoubleArray>("bridge_volume", m);
    auto bridge_force = named_array<vtkDoubleArray>("bridge_force", m);
    bridge_volume->Fill(0.0);
    bridge_force->Fill(0.0);
    for (std::size_t b = 0; b < bonds.size(); ++b) {
      const auto k = static_cast<vtkIdType>(bond_line[b]);
      bridge_volume->SetValue(k, bonds[b].volume);
      bridge_force->SetValue(k, bonds[b].force);
    }
    pd->GetCellData()->AddArray(bridge_volume);
    pd->GetCellData()->AddArray(bridge_force);
  }
  pd->GetCellData()->SetActiveScalars("force_magnitude");
  return pd;
}

}  // namespace drumlab::render
