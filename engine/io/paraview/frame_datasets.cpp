#include "engine/io/paraview/frame_datasets.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "engine/analysis/agglomerates.hpp"
#include "engine/drum.hpp"
#include "engine/periodic.hpp"

namespace drumlab::paraview {
namespace {

template <class T>
std::vector<T> copy_of(std::span<const T> values) {
  return {values.begin(), values.end()};
}

std::vector<double> flat(std::span<const Vec3> values) {
  std::vector<double> out(3 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::copy(values[i].data(), values[i].data() + 3, out.begin() + 3 * static_cast<long>(i));
  }
  return out;
}

/// A line from a to the image of b nearest to it, as two new points.
void add_line(DataSet& d, const Vec3& a, const Vec3& b, double period) {
  const auto first = static_cast<std::int64_t>(d.points.size());
  d.points.push_back(a);
  d.points.push_back(a - nearest_image(a, b, period));
  d.add_cell({first, first + 1});
}

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

}  // namespace

DataSet particles(const ParticleFields& f) {
  DataSet d;
  d.points = copy_of(f.position);
  std::vector<double> speed(f.velocity.size());
  std::transform(f.velocity.begin(), f.velocity.end(), speed.begin(),
                 [](const Vec3& v) { return v.norm(); });
  auto& pd = d.point_data;
  pd.push_back(make_array("id", copy_of(f.id)));
  pd.push_back(make_array("radius", copy_of(f.radius)));
  pd.push_back(make_array("size_class", copy_of(f.size_class)));
  pd.push_back(make_array("velocity", flat(f.velocity), 3));
  pd.push_back(make_array("speed", std::move(speed)));
  pd.push_back(make_array("angular_velocity", flat(f.omega), 3));
  if (!f.force.empty()) pd.push_back(make_array("force", flat(f.force), 3));
  if (!f.coordination.empty()) pd.push_back(make_array("coordination", copy_of(f.coordination)));
  if (!f.agglomerate_id.empty()) {
    pd.push_back(make_array("agglomerate_id", copy_of(f.agglomerate_id)));
    pd.push_back(make_array("liquid_volume", copy_of(f.liquid_volume)));
  }
  d.active_scalars = "radius";
  d.active_vectors = "velocity";
  return d;
}

DataSet particles(const Simulation& sim, const GranuleCriterion& granule) {
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
    label = agglomerate_labels(sim, granule);
    const std::vector<double>* film = p.find_array(kLiquidFilmArray);
    liquid = film ? *film : std::vector<double>(p.size(), 0.0);
    f.agglomerate_id = label;
    f.liquid_volume = liquid;
  }
  return particles(f);
}

DataSet particles(const SeriesFrame& frame) {
  ParticleFields f;
  f.position = frame.position;
  f.velocity = frame.velocity;
  f.omega = frame.omega;
  f.radius = frame.radius;
  f.id = frame.id;
  f.size_class = frame.size_class;
  f.agglomerate_id = frame.agglomerate_id;
  f.liquid_volume = frame.film;
  return particles(f);
}

DataSet drum(const Simulation& sim, int segments) {
  const DrumConfig& c = sim.scene().drum;
  const double r = 0.5 * c.diameter;
  const double h = c.depth;
  const double angle0 = sim.drum_angle();
  DataSet d;
  d.cells = CellKind::polygons;
  // Points: ring k at z = 0 is 2k, at z = H is 2k + 1, starting at the drum angle.
  for (int k = 0; k < segments; ++k) {
    const double a = angle0 + 2.0 * std::numbers::pi * k / segments;
    d.points.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    d.points.emplace_back(r * std::cos(a), r * std::sin(a), h);
  }
  std::vector<std::uint8_t> part, marker;
  const int stripe = std::max(1, segments / 24);
  for (int k = 0; k < segments; ++k) {
    const std::int64_t a = 2 * k;
    const std::int64_t b = 2 * ((k + 1) % segments);
    d.add_cell({a, b, b + 1, a + 1});
    part.push_back(0);
    marker.push_back(k < stripe ? 1 : 0);
  }
  if (c.ends == DrumEnds::caps) {
    for (int cap = 0; cap < 2; ++cap) {
      for (int k = 0; k < segments; ++k) {
        // Outward normals: the low cap runs clockwise seen from +z, the high cap anticlockwise.
        const int kk = cap == 0 ? segments - 1 - k : k;
        d.connectivity.push_back(2 * kk + cap);
      }
      d.offsets.push_back(static_cast<std::int64_t>(d.connectivity.size()));
      part.push_back(static_cast<std::uint8_t>(1 + cap));
      marker.push_back(0);
    }
  }
  d.cell_data.push_back(make_array("part", std::move(part)));
  d.cell_data.push_back(make_array("marker", std::move(marker)));
  d.field_data.push_back(make_array("drum_angle", std::vector<double>{sim.drum_angle()}));
  d.field_data.push_back(make_array("drum_omega", std::vector<double>{sim.drum_omega()}));
  return d;
}

DataSet contacts(const Simulation& sim) {
  std::vector<ContactForce> forces;
  sim.contact_forces(forces);
  std::vector<Bond> bond_list;
  sim.bonds(bond_list);
  const std::vector<std::size_t> bond_line = bond_lines(bond_list, forces);
  const Particles& p = sim.particles();
  const double period = Drum(sim.scene().drum).period();
  DataSet d;
  d.cells = CellKind::lines;
  std::vector<double> magnitude, force;
  std::vector<std::uint32_t> id_a, id_b;
  for (const ContactForce& c : forces) {
    add_line(d, p.position[c.i], p.position[c.j], period);
    magnitude.push_back(c.force.norm());
    force.insert(force.end(), c.force.data(), c.force.data() + 3);
    id_a.push_back(p.id[c.i]);
    id_b.push_back(p.id[c.j]);
  }
  d.cell_data.push_back(make_array("force_magnitude", std::move(magnitude)));
  d.cell_data.push_back(make_array("force", std::move(force), 3));
  d.cell_data.push_back(make_array("id_a", std::move(id_a)));
  d.cell_data.push_back(make_array("id_b", std::move(id_b)));
  if (scene_has_bonds(sim.scene())) {  // each bond's volume and force on its line, 0 elsewhere
    std::vector<double> volume(forces.size(), 0.0), bridge(forces.size(), 0.0);
    for (std::size_t b = 0; b < bond_list.size(); ++b) {
      volume[bond_line[b]] = bond_list[b].volume;
      bridge[bond_line[b]] = bond_list[b].force;
    }
    d.cell_data.push_back(make_array("bridge_volume", std::move(volume)));
    d.cell_data.push_back(make_array("bridge_force", std::move(bridge)));
  }
  d.active_scalars = "force_magnitude";
  return d;
}

DataSet bonds(const SeriesFrame& frame) {
  DataSet d;
  d.cells = CellKind::lines;
  std::vector<double> volume, force, age;
  std::vector<std::uint32_t> id_a, id_b;
  for (const Bond& b : frame.bonds) {
    add_line(d, frame.position[b.i], frame.position[b.j], frame.period);
    volume.push_back(b.volume);
    force.push_back(b.force);
    age.push_back(b.age);
    id_a.push_back(frame.id[b.i]);
    id_b.push_back(frame.id[b.j]);
  }
  d.cell_data.push_back(make_array("bridge_volume", std::move(volume)));
  d.cell_data.push_back(make_array("bridge_force", std::move(force)));
  d.cell_data.push_back(make_array("age", std::move(age)));
  d.cell_data.push_back(make_array("id_a", std::move(id_a)));
  d.cell_data.push_back(make_array("id_b", std::move(id_b)));
  d.active_scalars = "bridge_force";
  return d;
}

}  // namespace drumlab::paraview
