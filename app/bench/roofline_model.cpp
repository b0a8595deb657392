#include "app/bench/roofline_model.hpp"

#include <type_traits>
#include <variant>

#include "engine/contact/contact_model.hpp"

namespace drumlab::bench {

namespace {
constexpr double kVec = 24.0;  // bytes of a Vec3
constexpr double kIdx = 4.0;   // bytes of an Index
}  // namespace

LawShape law_shape(const SceneConfig& scene, const Particles& particles) {
  const ContactModel model(scene);
  LawShape s;
  s.hertz = std::holds_alternative<HertzNormal>(model.pair_normal());
  s.wall_hertz = std::holds_alternative<HertzNormal>(model.wall_normal());
  s.tangential = model.pair_tangential();
  s.rolling = model.pair_rolling();
  s.wall_tangential = model.wall_tangential();
  s.wall_rolling = model.wall_rolling();
  s.rotation = model.uses_rotation();
  s.cohesive = model.cohesive_parts().any();
  particles.for_each_array([&](std::string_view, const auto& array) {
    s.particle_bytes += sizeof(typename std::decay_t<decltype(array)>::value_type);
  });
  return s;
}

// split_row (contact_model.cpp): separation 3, sum_r 1, |d|^2 5, cut 1, two squares 2. Reads the
// partner's index (stream), position and radius (gather); writes the history of an entry that
// does not overlap (stream; an overlapping one is counted in touching_pair_cost).
Work listed_pair_cost() {
  return {12.0, 0.0, kIdx + kVec, kVec + 8.0};
}

// PairBatch::gather (add, one lane at a time): separation 3, inverse mass and inertia sums 2,
// relative velocity 3 = 8.
// PairBatch::evaluate geometry: sum_r 1, |d|^2 5, delta 1, the unit normal d (1/|d|) 3,
//   (r_i + r_j)(1/m_i + 1/m_j) 1, r_eff 3, m_eff 1, a_i a_j 4, stop_rate 1 = 20; sqrt(|d|^2),
//   1/|d| and the one division that gives r_eff and m_eff = 3 divsqrt.
// contact_response, tangential: spin velocity at the contact 21, v_n 5, HertzNormal::respond 10
//   (2 sqrt), v_t 6, MindlinTangential::force_of 59 (sqrt and division of the rescale, sqrt and
//   division of the cap, the division 1/S_t and 3 products of xi_slide), torques and force 21 =
//   122, 7 divsqrt.
// Without tangential: v_n 5, HertzNormal::force 7 (2 sqrt), force 3 = 15 flops, 2 divsqrt;
//   LinearSpringDashpot::force 6 (1 sqrt: the damping's), so 14 flops, 1 divsqrt. With
//   tangential, LinearSpringDashpot::respond is 10 flops and 2 sqrt, as HertzNormal::respond.
// Rolling (RollingResistance::torque_of): 20 flops, the norm's sqrt and two divisions.
// Scatter (RowSum and the partner's share): force and torque of both = 12.
// Bytes: the history read (its write is in listed_pair_cost); the partner's velocity, spin,
// inverse mass and inertia (gather, 64) and its force and torque (read and written, 96).
namespace {
// contact_response without the tangential part: v_n, the normal force, the force vector.
Work normal_only_response(bool hertz) {
  return hertz ? Work{15.0, 2.0, 0.0, 0.0} : Work{14.0, 1.0, 0.0, 0.0};
}
}  // namespace

Work touching_pair_cost(const LawShape& s) {
  Work w{8.0 + 20.0 + 12.0, 3.0, kVec, 64.0 + 96.0};
  if (s.tangential) {
    w += {122.0, 7.0, 0.0, 0.0};
  } else {
    w += normal_only_response(s.hertz) + Work{0.0, 0.0, -kVec, 0.0};  // no history
  }
  if (s.rolling) w += {20.0, 3.0, 0.0, 0.0};
  return w;
}

// cohesion_loops.cpp on a live bridge: separation and gap 9 with a sqrt, Willett's s~ = s sqrt(R/V)
// (a division and a sqrt) and F = F0 / (1 + (1.05 + 2.5 s~) s~) (4 and a division), the unit
// normal (a division, 3 products), force on both 12, rupture test 3: 31 flops, 4 divsqrt; the
// bridge state (2 doubles) read and written, the partner's position and film gathered.
Work cohesive_pair_cost() {
  return {31.0, 4.0, 32.0, kVec + 8.0};
}

// Drum::contact on a wall candidate: radial distance 3 with a sqrt, mantle gap 2, cap gaps 4,
// the mantle normal's 2 divisions, the wall's surface velocity omega x r 5 = 14 flops, 3 divsqrt;
// reads the candidate's index (stream), position and radius (gather).
Work wall_candidate_cost() {
  return {14.0, 3.0, kIdx, kVec + 8.0};
}

// WallBatch::evaluate: a_i 2, relative velocity 3, contact_response as for a pair (without the
// partner's spin), scatter of force and torque 6; the wall history read and written (stream),
// velocity, spin, mass, force and torque (gather).
Work wall_contact_cost(const LawShape& s) {
  Work w{2.0 + 3.0 + 6.0, 0.0, 2.0 * kVec, 3.0 * kVec + 8.0 + 4.0 * kVec};
  w += s.wall_tangential ? Work{122.0 - 9.0, 7.0, 0.0, 0.0}
                         : normal_only_response(s.wall_hertz) + Work{0.0, 0.0, -2.0 * kVec, 0.0};
  if (s.wall_rolling) w += {20.0, 3.0, 0.0, 0.0};
  return w;
}

// Simulation::kick_drift and kick: v += h (F/m + g) twice (12 each), omega += h/I T twice (7
// each), |v|^2 5, x += dt v 6. kick_drift reads v, F, omega, T, x, 1/m, 1/I and writes v, omega,
// F = 0, T = 0, x (256 bytes); kick reads v, F, 1/m, omega, T, 1/I and writes v, omega (160).
Work integrated_particle_cost(const LawShape& s) {
  if (s.rotation) return {12.0 * 2 + 7.0 * 2 + 5.0 + 6.0, 0.0, 256.0 + 160.0, 0.0};
  return {12.0 * 2 + 5.0 + 6.0, 0.0, 176.0 + 104.0, 0.0};
}

// spatial_order.cpp: the Morton key (3 subtractions, 3 products), sorting (key, index) pairs
// (16 bytes, a few passes: 4 counted), and every particle array permuted: read at scattered
// places, written in order. The lists' renumbering is in RunCounts (per listed pair).
Work reordered_particle_cost(const LawShape& s) {
  const double b = static_cast<double>(s.particle_bytes);
  return {6.0, 0.0, 4.0 * 2.0 * 16.0 + b, b};
}

// A grid search's or a Verlet rebuild's distance test: as listed_pair_cost, without the history.
Work tested_pair_cost() {
  return {12.0, 0.0, kIdx, kVec + 8.0};
}

// Binning: the cell of a particle (3 subtractions, 3 products), its position read, its cell and
// its place in the cell's list written.
Work binned_particle_cost() {
  return {6.0, 0.0, kVec + 4.0 + kIdx, 0.0};
}

// A Verlet list patch (verlet_list.cpp patch(), verlet_patch.cpp find()), per particle: the scan
// (position turned into the list's frame 6, squared distance to its reference 8; both read), the
// grid's bounds (the reference read; compares, not counted), its cell (3 subtractions, 3
// divisions; the reference read, the cell written), the counting sort (the cell read twice, the
// reference and radius read, index and packed reference written at the cell's slot; the cell's
// count read and written twice at scattered places). Its distance tests are the moved particles'
// alone (a few in a hundred move), not counted.
Work patched_particle_cost() {
  const double scan = 2.0 * kVec, bounds = kVec, cell = kVec + 4.0;
  const double sort = 2.0 * 4.0 + kVec + 8.0 + kIdx + 32.0;
  return {14.0 + 3.0, 3.0, scan + bounds + cell + sort, 2.0 * 4.0};
}

PhaseWork phase_work(const LawShape& s, const RunCounts& c) {
  const StepWork& w = c.work;
  const double steps = static_cast<double>(c.steps);
  const double particles_per_step = steps > 0 ? static_cast<double>(w.particles) / steps : 0.0;
  const double listed_per_step = steps > 0 ? static_cast<double>(w.listed_pairs) / steps : 0.0;
  PhaseWork p;
  // Search: each build bins every particle; its distance tests; the new list written and the
  // contacts' history carried over (index and history, read and written).
  const double builds = static_cast<double>(c.builds);
  p.search += binned_particle_cost() * (builds * particles_per_step);
  const double list_tests = c.verlet ? static_cast<double>(w.listed_pairs) : 0.0;
  const double tests = static_cast<double>(c.pairs_tested) - list_tests;
  p.search += tested_pair_cost() * (tests > 0.0 ? tests : 0.0);
  p.search += Work{0.0, 0.0, 2.0 * (kIdx + kVec), 0.0} * (builds * listed_per_step);
  // A patch: its pass over every particle; the list spliced (each pair read and written) and its
  // rows counted (read), and the contacts' history carried over as after a build.
  const double patches = static_cast<double>(c.patches);
  p.search += patched_particle_cost() * (patches * particles_per_step);
  p.search +=
      Work{0.0, 0.0, 3.0 * 2.0 * kIdx + 2.0 * (kIdx + kVec), 0.0} * (patches * listed_per_step);
  // Forces: every listed pair, the touching ones, the live cohesive links.
  p.forces += listed_pair_cost() * static_cast<double>(w.listed_pairs);
  p.forces += touching_pair_cost(s) * static_cast<double>(w.touching_pairs);
  p.forces += cohesive_pair_cost() * (c.cohesive_pairs_per_step * steps);
  p.forces += Work{0.0, 0.0, kVec * 2.0, 0.0} * static_cast<double>(w.particles);  // own F, T
  p.walls += wall_candidate_cost() * static_cast<double>(w.wall_candidates);
  p.walls += wall_contact_cost(s) * static_cast<double>(w.wall_contacts);
  p.integration += integrated_particle_cost(s) * static_cast<double>(w.particles);
  const double reorders = static_cast<double>(w.reorders);
  p.reorder += reordered_particle_cost(s) * (reorders * particles_per_step);
  p.reorder += Work{0.0, 0.0, 2.0 * 2.0 * (kIdx + kVec), 0.0} * (reorders * listed_per_step);
  // One step of the pair loop touches every particle array it reads (position, radius,
  // velocity, spin, inverse mass and inertia, force, torque: 152 bytes) and the list with its
  // history.
  p.working_set_particles = particles_per_step * static_cast<double>(s.particle_bytes);
  p.working_set_forces = particles_per_step * 152.0 + listed_per_step * (kIdx + kVec);
  return p;
}

}  // namespace drumlab::bench
