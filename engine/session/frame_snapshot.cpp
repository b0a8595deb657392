#include "engine/session/frame_snapshot.hpp"
#include "engine/spray/droplet_cloud.hpp"

#include <algorithm>
#include <cmath>

#include "engine/search/cell_grid.hpp"
#include "engine/search/verlet_list.hpp"

namespace drumlab {

const CellGridSearch* drawn_cell_grid(const ContactSearch& search) {
  if (const auto* grid = dynamic_cast<const CellGridSearch*>(&search)) return grid;
  if (const auto* list = dynamic_cast<const VerletListSearch*>(&search)) {
    return dynamic_cast<const CellGridSearch*>(&list->builder());
  }
  return nullptr;
}

CellCoord cell_containing(const GridGeometry& g, const Vec3& x) {
  const Vec3 u = (x - g.origin) / g.cell_xy;
  CellCoord c{std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(u.x())), 0, g.nx - 1),
              std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(u.y())), 0, g.ny - 1),
              0};
  if (g.nz > 1) {
    const double uz = (x.z() - g.origin.z()) / g.cell_z;
    c.z = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(uz)), 0, g.nz - 1);
  }
  return c;
}

namespace {

std::vector<ClassCounters> class_counters(const Simulation& sim,
                                          const std::vector<std::uint32_t>& coordination) {
  const Particles& p = sim.particles();
  const auto& classes = sim.scene().classes;
  std::vector<ClassCounters> out(classes.size());
  for (std::size_t k = 0; k < classes.size(); ++k) {
    out[k].name = classes[k].name;
    out[k].radius = classes[k].mean_radius();
  }
  const auto cells = sim.search().cells_visited_per_particle();
  const auto tests = sim.search().pairs_tested_per_particle();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t k = p.size_class[i];
    if (k >= out.size()) continue;  // a packing read from a file may carry radii of no class
    ClassCounters& c = out[k];
    ++c.particles;
    if (i < cells.size()) c.cells_visited += cells[i];
    if (i < tests.size()) c.pairs_tested += tests[i];
    c.contacts += coordination[i];
  }
  return out;
}

}  // namespace

FrameSnapshot take_snapshot(const Simulation& sim, const SnapshotRequest& request) {
  const Particles& p = sim.particles();
  const ContactSearch& search = sim.search();
  FrameSnapshot s;
  s.scene_name = sim.scene().name;
  s.drum_radius = 0.5 * sim.scene().drum.diameter;
  s.drum_depth = sim.scene().drum.depth;
  s.scene_omega = sim.scene().drum.omega;
  s.classes = sim.scene().classes;
  s.sprays = sim.scene().sprays;
  s.meshes = sim.wall_meshes();

  s.position = p.position;
  s.velocity = p.velocity;
  s.omega = p.omega;
  s.radius = p.radius;
  s.id = p.id;
  s.size_class = p.size_class;
  sim.coordination_numbers(s.coordination);
  if (const DropletCloud* cloud = sim.spray()) {
    for (const Droplet& d : cloud->droplets()) s.droplets.push_back(d.position);
  }

  s.time = sim.time();
  s.dt = sim.dt();
  s.drum_angle = sim.drum_angle();
  s.drum_omega = sim.drum_omega();
  s.orbit_radius = sim.scene().drum.orbit.radius;
  s.carrier_angle = sim.carrier_angle();
  s.carrier_offset = sim.carrier_offset();
  s.steps = sim.steps();

  s.search_name = search.name();
  s.search_description = search.description();
  s.counters = search.counters();
  s.totals = sim.search_totals();
  s.search_timings = search.timings();
  s.timers = sim.timers();
  s.per_class = class_counters(sim, s.coordination);
  if (const CellGridSearch* grid = drawn_cell_grid(search)) s.grid = grid->geometry();
  s.lists_pairs = dynamic_cast<const VerletListSearch*>(&search) != nullptr;
  if (request.diagnostics) s.diagnostics = sim.diagnostics();

  if (request.focus_id) {
    const auto it = std::find(p.id.begin(), p.id.end(), *request.focus_id);
    if (it != p.id.end()) s.focus_index = static_cast<Index>(it - p.id.begin());
  }
  // A grid that has not searched yet (no step so far) has nothing to replay.
  const bool searched = !s.grid || s.grid->nx > 0;
  if (s.focus_index && searched) {
    const SearchInput in = sim.search_input();
    s.focus_visit = search.visit(*s.focus_index, in);
    std::vector<IndexPair> pairs;
    for (const std::string& name : request.compare_methods) {
      auto other = make_search(name, {});
      other->find_pairs(in, pairs);
      s.compare_visits.push_back({name, other->visit(*s.focus_index, in)});
    }
  }
  return s;
}

}  // namespace drumlab
