#include "engine/io/paraview/frame_datasets.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include <Eigen/Geometry>

#include "engine/analysis/agglomerates.hpp"
#include "engine/drum.hpp"
#include "engine/periodic.hpp"
#include "engine/spray/droplet_cloud.hpp"

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

DataSet droplets(const Simulation& sim) {
  DataSet d;
  std::vector<double> velocity, radius;
  std::vector<std::uint32_t> spray;
  if (const DropletCloud* cloud = sim.spray()) {
    for (const Droplet& q : cloud->droplets()) {
      d.points.push_back(q.position);
      velocity.insert(velocity.end(), q.velocity.data(), q.velocity.data() + 3);
      radius.push_back(cloud->sprays()[q.spray].droplet_radius);
      spray.push_back(q.spray);
    }
  }
  d.point_data.push_back(make_array("velocity", std::move(velocity), 3));
  d.point_data.push_back(make_array("radius", std::move(radius)));
  d.point_data.push_back(make_array("spray", std::move(spray)));
  d.active_scalars = "radius";
  d.active_vectors = "velocity";
  return d;
}

DataSet nozzles(std::span<const SprayConfig> sprays, double drum_diameter) {
  DataSet d;
  d.cells = CellKind::lines;
  std::vector<std::uint32_t> index;
  const double length = 0.25 * drum_diameter;
  for (std::size_t s = 0; s < sprays.size(); ++s) {
    const SprayConfig& c = sprays[s];
    const Vec3 axis = c.direction.normalized();
    const Vec3 helper = std::abs(axis.x()) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
    Vec3 e1 = axis.cross(helper).normalized();
    if (c.shape == SprayShape::flat_fan) {
      const Vec3 f = c.fan_axis - c.fan_axis.dot(axis) * axis;
      if (f.norm() > 1e-12) e1 = f.normalized();
    }
    const Vec3 e2 = axis.cross(e1);
    const double half = 0.5 * c.angle_deg * std::numbers::pi / 180.0;
    const auto origin = static_cast<std::int64_t>(d.points.size());
    d.points.push_back(c.position);
    d.points.push_back(c.position + length * axis);
    d.add_cell({origin, origin + 1});
    index.push_back(static_cast<std::uint32_t>(s));
    const bool fan = c.shape == SprayShape::flat_fan;
    const int rays = fan ? 9 : 16;
    const auto first = static_cast<std::int64_t>(d.points.size());
    for (int k = 0; k < rays; ++k) {
      Vec3 dir;
      if (fan) {
        const double theta = -half + 2.0 * half * k / (rays - 1);
        dir = std::cos(theta) * axis + std::sin(theta) * e1;
      } else {
        const double phi = 2.0 * std::numbers::pi * k / rays;
        dir = std::cos(half) * axis + std::sin(half) * (std::cos(phi) * e1 + std::sin(phi) * e2);
      }
      d.points.push_back(c.position + length * dir);
      d.add_cell({origin, first + k});
      index.push_back(static_cast<std::uint32_t>(s));
    }
    const int ends = fan ? rays - 1 : rays;  // the fan's arc, the cone's closed ring
    for (int k = 0; k < ends; ++k) {
      d.add_cell({first + k, first + (k + 1) % rays});
      index.push_back(static_cast<std::uint32_t>(s));
    }
  }
  d.cell_data.push_back(make_array("spray", std::move(index)));
  d.active_scalars = "spray";
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
