#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include <fmt/format.h>

#include "engine/block_dealer.hpp"
#include "engine/contact/contact_history.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/contact/liquid_start.hpp"
#include "engine/contact/mesh_wall_history.hpp"
#include "engine/contact/wall_candidates.hpp"
#include "engine/drum.hpp"
#include "engine/integration_lanes.hpp"
#include "engine/io/restart_check.hpp"
#include "engine/mesh/mesh_wall_set.hpp"
#include "engine/periodic.hpp"
#include "engine/search/verlet_list.hpp"
#include "engine/spatial_order.hpp"
#include "engine/spray/droplet_cloud.hpp"
#include "engine/stability.hpp"

namespace drumlab {

using Clock = std::chrono::steady_clock;

namespace {

/// "Centre outside the drum" tolerance, relative to the drum radius (round-off only).
constexpr double kOutsideTolerance = 1e-9;

/// Particles a block of the integration's passes (BlockDealer): 2,048 particles stream about
/// 450 kB, enough that dealing costs nothing against them.
constexpr std::size_t kIntegrationBlock = 2048;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

std::string scene_label(const SceneConfig& s) {
  if (!s.source.empty()) return s.source;
  return s.name.empty() ? std::string("scene") : s.name;
}

double smallest_radius(const SceneConfig& scene, const Particles& p) {
  if (!p.empty()) return p.min_radius();
  double r = std::numeric_limits<double>::infinity();
  for (const ParticleClass& c : scene.classes) r = std::min(r, c.min_radius());
  return r;
}

/// Sums and maxima of the ranks' diagnostics (a decomposed run: every rank calls this together).
void reduce_diagnostics(DomainHooks& domain, Diagnostics& d) {
  for (double* v : {&d.kinetic_energy, &d.rotational_energy, &d.potential_energy, &d.elastic_energy,
                    &d.liquid_volume, &d.lab_kinetic_energy}) {
    *v = domain.sum(*v);
  }
  for (std::size_t* v : {&d.outside_drum, &d.non_finite, &d.contacts, &d.wall_contacts, &d.bridges,
                         &d.wall_bridges}) {
    *v = static_cast<std::size_t>(domain.sum(static_cast<std::uint64_t>(*v)));
  }
  const double local = d.max_overlap_ratio;
  d.max_overlap_ratio = domain.max(d.max_overlap_ratio);
  reduce_overlap_site(domain, local, d.max_overlap_ratio, d.max_overlap_site);
}

}  // namespace

double rayleigh_time(double radius, const Material& m) {
  const double g = m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
  return std::numbers::pi * radius * std::sqrt(m.density / g) / (0.1631 * m.poisson_ratio + 0.8766);
}

namespace {

/// Undamped half-period pi sqrt(m*/k) (s) of a linear normal law for a contact of effective mass
/// m_eff; nullopt for Hertz, whose stiffness grows with the overlap (the Rayleigh time bounds it).
std::optional<double> linear_half_period(const NormalVariant& law, double m_eff) {
  return std::visit(
      [m_eff](const auto& l) -> std::optional<double> {
        using Law = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<Law, HertzNormal>) {
          return std::nullopt;
        } else {
          return std::numbers::pi * std::sqrt(m_eff / l.stiffness);
        }
      },
      law);
}

/// A restart's contact and wall history must be finite: a NaN spring would spread through the
/// contact's forces into the whole bed at the first step.
void check_history_finite(const SimulationState& state) {
  const auto refuse = [](std::string_view dataset, std::size_t row) {
    throw InputError(fmt::format("restart state: {}: row {}: not finite", dataset, row));
  };
  for (std::size_t k = 0; k < state.contact_history.size(); ++k) {
    if (!state.contact_history[k].allFinite()) refuse("contacts/history", k);
  }
  for (std::size_t k = 0; k < state.contact_state.size(); ++k) {
    if (!std::isfinite(state.contact_state[k])) {
      refuse("contacts/state", k / std::max<std::size_t>(state.contact_state_size, 1));
    }
  }
  for (std::size_t i = 0; i < state.wall_history.size(); ++i) {
    for (const Vec3& v : state.wall_history[i]) {
      if (!v.allFinite()) refuse("walls/history", i);
    }
  }
}

}  // namespace

std::optional<double> viscous_relaxation_time(const SceneConfig& scene, double r_min) {
  const LiquidConfig& l = scene.liquid;
  if (!l.enabled || !(l.viscosity > 0.0) || !(l.min_gap > 0.0)) return std::nullopt;
  const double lightest =
      scene.material.density * 4.0 / 3.0 * std::numbers::pi * r_min * r_min * r_min;
  const auto time = [&](double m_eff, double r_star) {
    return m_eff * l.min_gap / (6.0 * std::numbers::pi * l.viscosity * r_star * r_star);
  };
  const double pair = time(0.5 * lightest, 0.5 * r_min);
  return l.wall_bridges ? std::min(pair, time(lightest, r_min)) : pair;
}

TimeStepLimit time_step_limit(const SceneConfig& scene, const ContactModel& model, double r_min) {
  const double lightest =
      scene.material.density * 4.0 / 3.0 * std::numbers::pi * r_min * r_min * r_min;
  const std::optional<double> pair_period = linear_half_period(model.pair_normal(), 0.5 * lightest);
  const std::optional<double> wall_period = linear_half_period(model.wall_normal(), lightest);
  TimeStepLimit contact{kMaxSafeDtFactor, rayleigh_time(r_min, scene.material), "Rayleigh times"};
  if (pair_period || wall_period) {
    const double period = std::min(pair_period.value_or(HUGE_VAL), wall_period.value_or(HUGE_VAL));
    contact = {kMaxSafeLinearDtFactor, period,
               "contact half-periods of the linear contact law (pi sqrt(m*/k) of the lightest "
               "particles)"};
  }
  // An explicit step of the bridges' viscous term reverses a relative velocity once
  // dt c / m* > 1 (and grows without bound past 2): dt stays within one relaxation time.
  const std::optional<double> viscous = viscous_relaxation_time(scene, r_min);
  if (viscous && *viscous < contact.seconds()) {
    return {1.0, *viscous,
            "viscous relaxation times (m*/c of the lightest bridge, c = 6 pi liquid.viscosity "
            "R*^2 / liquid.min_gap)"};
  }
  return contact;
}

struct Simulation::Impl {
  explicit Impl(const SceneConfig& s) : drum(s.drum), model(s) {}
  Drum drum;
  ContactModel model;
  ContactList contacts;
  std::vector<IndexPair> pairs;
  std::vector<IndexPair> computed;  ///< a rank's found pairs without those of two ghosts
  WallHistory wall_history;
  PairForceBuffers pair_buffers;
  BlockDealer integration_blocks;  ///< deals the particles to the threads in kick and kick_drift
  /// The active search if it is a Verlet list: the simulation then keeps the history on the
  /// listed pairs and tests them in the force loop (see VerletListSearch).
  VerletListSearch* verlet = nullptr;
  ReorderBuffers reorder;
  WallHistory wall_scratch;
  WallCandidates walls;
  double wall_reach = -1.0;  ///< m; set on the first force evaluation (radii do not change)
  /// Bound on how far any particle moved (nearest image along periodic ends) since the last
  /// force evaluation, m; infinite when not known. Lets the Verlet and wall lists skip their
  /// per-particle displacement checks.
  double moved = std::numeric_limits<double>::infinity();
  bool forces_cleared = false;  ///< by kick_drift(), for the force evaluation that follows
  /// Each particle's liquid not put in its film at the start (LiquidConfig::film_share < 1), for
  /// the bridges of the first evaluation (seed_bridges); empty afterwards.
  std::vector<double> liquid_reserve;
  /// A decomposed run's replay of this step's bridge events (replay_bridge_events).
  BridgeEventFilms bridge_replay;
  /// The triangle walls ([[wall.mesh]], [[wall.lifters]]); empty without: nothing to pay.
  MeshWallSet meshes;
  /// The meshes' triangles for pictures and files (wall_meshes()); null without.
  std::shared_ptr<const std::vector<WallMesh>> wall_meshes;
  /// The binder droplets of a scene with [[spray]] (engine/spray/droplet_cloud.hpp); null
  /// without: a scene without spray pays nothing.
  std::unique_ptr<DropletCloud> spray;
};

Simulation::Simulation(const SceneConfig& scene, Particles particles, SimulationOptions options)
    : scene_(scene), particles_(std::move(particles)) {
  impl_ = std::make_unique<Impl>(scene_);
  use_search(make_search(scene_.search_method, search_tuning()));
  gravity_ = drum_frame_gravity(scene_.gravity, scene_.drum.tilt);
  omega_ = scene_.drum.omega;
  if (scene_.drum.orbit.active()) {
    carrier_angle_ = scene_.drum.orbit.phase;
    carrier_omega_ = scene_.drum.orbit.omega;
  }
  make_meshes();
  validate_particles();
  choose_time_step(options);
  impl_->wall_history.assign(particles_.size(), {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  impl_->contacts.set_state_size(impl_->model.pair_state_size());
  register_liquid_arrays(true);
  if (!scene_.sprays.empty()) make_spray();
  // Forces of the initial state, for the first half kick (no history increment, not counted).
  compute_forces(0.0, false);
}

Simulation::Simulation(const SceneConfig& scene, SimulationState state)
    : scene_(scene), particles_(std::move(state.particles)) {
  if (!state.search_method.empty()) scene_.search_method = state.search_method;
  if (scene_.sprays.empty() != state.spray.empty()) {
    throw InputError(scene_.sprays.empty()
                         ? "restart state: it carries binder droplets, the scene has no [[spray]]"
                         : "restart state: the scene has [[spray]], the state carries no droplets "
                           "(a checkpoint of a scene without spray)");
  }
  impl_ = std::make_unique<Impl>(scene_);
  use_search(make_search(scene_.search_method, search_tuning()));
  gravity_ = drum_frame_gravity(scene_.gravity, scene_.drum.tilt);
  const std::size_t n = particles_.size();
  if (particles_.radius.size() != n || particles_.size_class.size() != n ||
      particles_.id.size() != n) {
    throw InputError("restart state: particle arrays of different lengths");
  }
  make_meshes();
  validate_particles();
  check_restart_particles(scene_, particles_, "restart state");
  if (!(state.dt > 0.0) || !std::isfinite(state.dt) || !std::isfinite(state.time) ||
      !std::isfinite(state.drum_angle) || !std::isfinite(state.drum_omega)) {
    throw InputError("restart state: dt must be positive, time/angle/omega finite");
  }
  if (state.wall_history.size() != n) {
    throw InputError("restart state: wall history does not match the particle count");
  }
  if (!state.contact_row_start.empty() && state.contact_row_start.size() != n + 1) {
    throw InputError("restart state: contact list does not match the particle count");
  }
  check_history_finite(state);
  if (state.contact_state_size != impl_->model.pair_state_size()) {
    throw InputError(fmt::format(
        "restart state: {} scalars per contact, the scene's contact law keeps {} (a dry and a wet "
        "scene do not mix)",
        state.contact_state_size, impl_->model.pair_state_size()));
  }
  register_liquid_arrays(false);
  check_mesh_history();
  impl_->contacts.set_state_size(state.contact_state_size);
  impl_->contacts.assign(state.contact_row_start, state.contact_col, state.contact_history,
                         state.contact_state);
  impl_->wall_history = std::move(state.wall_history);
  rayleigh_time_ = drumlab::rayleigh_time(smallest_radius(scene_, particles_), scene_.material);
  dt_ = state.dt;
  time_ = state.time;
  omega_ = state.drum_omega;
  drum_angle_ = state.drum_angle;
  steps_ = state.steps;
  if (!scene_.drum.orbit.active() && (state.carrier_angle != 0.0 || state.carrier_omega != 0.0)) {
    throw InputError(
        "restart state: it carries a planetary carrier, the scene has no [drum.orbit]");
  }
  if (!std::isfinite(state.carrier_angle) || !std::isfinite(state.carrier_omega)) {
    throw InputError("restart state: the carrier's angle and rate must be finite");
  }
  carrier_angle_ = state.carrier_angle;
  carrier_omega_ = state.carrier_omega;
  if (!scene_.sprays.empty()) {
    make_spray();
    impl_->spray->restore(std::move(state.spray));
  }
  // Forces and torques come with the state: recomputing them would advance nothing but could
  // differ in the last bit from those the uninterrupted run carries into its next half kick.
}

Simulation::~Simulation() = default;

void Simulation::make_meshes() {
  if (!scene_.has_meshes()) return;
  // The grids' cells: one largest diameter; their reach: the largest radius.
  const double r_max = particles_.empty() ? scene_.max_radius() : particles_.max_radius();
  std::vector<WallMesh> built = build_wall_meshes(scene_);
  impl_->wall_meshes = std::make_shared<const std::vector<WallMesh>>(built);
  impl_->meshes = MeshWallSet(std::move(built), 2.0 * r_max, r_max);
}

void Simulation::check_mesh_history() const {
  const auto patches = static_cast<double>(impl_->meshes.patches());
  for (const std::string_view name : kMeshPatchArrays) {
    const std::vector<double>* keys = particles_.find_array(name);
    if (keys == nullptr) continue;
    for (const double key : *keys) {
      if (!(key >= 0.0 && key <= patches && key == std::floor(key))) {
        throw InputError(fmt::format(
            "restart state: {} holds {}, the scene's triangle walls have {} patches (a checkpoint "
            "of other meshes?)",
            name, key, impl_->meshes.patches()));
      }
    }
  }
}

const MeshWallSet& Simulation::meshes() const {
  return impl_->meshes;
}

std::shared_ptr<const std::vector<WallMesh>> Simulation::wall_meshes() const {
  return impl_->wall_meshes;
}

void Simulation::make_spray() {
  // The wall film's patches: one largest particle diameter wide.
  double r_max = particles_.empty() ? scene_.max_radius() : 0.0;
  for (const double r : particles_.radius) r_max = std::max(r_max, r);
  impl_->spray = std::make_unique<DropletCloud>(scene_.sprays, impl_->drum, gravity_, 2.0 * r_max);
}

SimulationState Simulation::state() const {
  SimulationState s;
  state_into(s);
  return s;
}

const ContactList& Simulation::contacts() const {
  return impl_->contacts;
}

const WallHistory& Simulation::wall_history() const {
  return impl_->wall_history;
}

SimulationState Simulation::take_state() {
  SimulationState s;
  Particles kept;
  WallHistory wall;
  std::swap(kept, particles_);
  std::swap(wall, impl_->wall_history);
  state_into(s);  // the contacts and scalars (copied), no particles
  s.particles = std::move(kept);
  s.wall_history = std::move(wall);
  impl_->contacts.clear();
  return s;
}

void Simulation::state_into(SimulationState& s) const {
  s.particles = particles_;
  s.time = time_;
  s.dt = dt_;
  s.drum_omega = omega_;
  s.drum_angle = drum_angle_;
  s.carrier_angle = carrier_angle_;
  s.carrier_omega = carrier_omega_;
  s.steps = steps_;
  s.search_method = scene_.search_method;
  const ContactList& c = impl_->contacts;
  s.contact_row_start.assign(c.row_start().begin(), c.row_start().end());
  s.contact_col.assign(c.col().begin(), c.col().end());
  s.contact_history.assign(c.history().begin(), c.history().end());
  s.contact_state_size = c.state_size();
  s.contact_state.assign(c.state().begin(), c.state().end());
  if (impl_->spray) s.spray = impl_->spray->state();
  s.wall_history = impl_->wall_history;
}

void Simulation::contact_forces(std::vector<ContactForce>& out) const {
  const double period = impl_->drum.period();
  impl_->model.pair_forces(particles_, impl_->contacts, period, dt_, out);
  impl_->model.add_cohesive_forces(particles_, impl_->contacts, period, out);
}

void Simulation::bonds(std::vector<Bond>& out) const {
  impl_->model.bonds(particles_, impl_->contacts, impl_->drum.period(), out);
}

LiquidTotals Simulation::liquid() const {
  return liquid_totals(impl_->model.cohesive_parts(), particles_, impl_->contacts, ghost_);
}

void Simulation::register_liquid_arrays(bool fresh) {
  Particles& p = particles_;
  bool new_films = false;
  const std::size_t parts = impl_->drum.periodic() ? 1 : kWallParts;
  for (const std::string_view name : impl_->model.particle_arrays(parts)) {
    if (p.find_array(name) != nullptr) continue;
    if (!fresh) {
      throw InputError(
          fmt::format("restart state: the scene's contact law needs the particle array "
                      "'{}', which the checkpoint lacks",
                      name));
    }
    p.add_array(name, 0.0);
    new_films = new_films || name == kLiquidFilmArray;
  }
  if (new_films) fill_films(scene_, p, impl_->liquid_reserve);
}

void Simulation::coordination_numbers(std::vector<std::uint32_t>& out) const {
  out.assign(particles_.size(), 0);
  const Particles& p = particles_;
  const ContactList& contacts = impl_->contacts;
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const double period = impl_->drum.period();
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const Index j = col[k];
      const Vec3 dx = nearest_image(p.position[i], p.position[j], period);
      const double sum_r = p.radius[i] + p.radius[j];
      if (dx.squaredNorm() >= sum_r * sum_r) continue;
      ++out[i];
      ++out[j];
    }
  }
}

void Simulation::validate_particles() {
  Particles& p = particles_;
  const std::size_t n = p.size();
  if (p.position.size() != n || p.velocity.size() != n || p.omega.size() != n ||
      p.force.size() != n || p.torque.size() != n || p.mass.size() != n || p.inv_mass.size() != n ||
      p.inv_inertia.size() != n) {
    throw InputError("particles: arrays of different lengths");
  }
  for (const ParticleArray& a : p.extra) {
    if (a.values.size() != n) {
      throw InputError(fmt::format("particles: array '{}' of a different length", a.name));
    }
  }
  const Drum& drum = impl_->drum;
  // The nearest image is the only image a pair sees: no particle may reach two images of another,
  // by contact or by a bridge (MercuryDPM's ghost particles would see both).
  const double reach = 2.0 * p.max_radius() + impl_->model.max_pair_range();
  if (drum.periodic() && n > 0 && !(drum.depth() > 2.0 * reach)) {
    throw InputError(fmt::format(
        "{}: drum.depth = {} m is too short for periodic ends (a particle would reach two images "
        "of another: must exceed 2 x (2 x the largest radius {} m + the bridges' reach {} m) = {} "
        "m)",
        scene_label(scene_), drum.depth(), p.max_radius(), impl_->model.max_pair_range(),
        2.0 * reach));
  }
  for (std::size_t i = 0; i < n; ++i) {
    Vec3& x = p.position[i];
    if (!x.allFinite() || !p.velocity[i].allFinite() || !p.omega[i].allFinite()) {
      throw InputError(fmt::format("particle {}: non-finite position or velocity", i));
    }
    if (drum.periodic()) x.z() = drum.wrap_z(x.z());
    if (!drum.contains_centre(x, 0.0)) {
      throw InputError(
          fmt::format("{}: particle {} at ({:.6g}, {:.6g}, {:.6g}) m lies outside the drum (R = {} "
                      "m, H = {} m)",
                      scene_label(scene_), i, x.x(), x.y(), x.z(), drum.radius(), drum.depth()));
    }
    // The overlap a run may reach (time.max_overlap, half a radius by default) is also what a
    // start may hold: a state saved by a run under a raised limit restarts under it.
    for (std::size_t part = 0; part < kWallParts; ++part) {
      const WallContact c = drum.contact(static_cast<WallPart>(part), x, p.radius[i]);
      if (c.overlap > scene_.time.max_overlap * p.radius[i]) {
        throw InputError(fmt::format(
            "{}: particle {} at ({:.6g}, {:.6g}, {:.6g}) m penetrates the drum wall by {:.3g} m "
            "(more than time.max_overlap = {} of its radius {:.3g} m)",
            scene_label(scene_), i, x.x(), x.y(), x.z(), c.overlap, scene_.time.max_overlap,
            p.radius[i]));
      }
    }
  }
}

void Simulation::choose_time_step(const SimulationOptions& options) {
  const double r_min = smallest_radius(scene_, particles_);
  if (!(r_min > 0.0) || !std::isfinite(r_min)) {
    throw InputError(fmt::format("{}: no particles and no particle classes to choose dt from",
                                 scene_label(scene_)));
  }
  rayleigh_time_ = drumlab::rayleigh_time(r_min, scene_.material);
  const double factor =
      options.dt_factor_override > 0.0 ? options.dt_factor_override : scene_.time.dt_factor;
  dt_ = scene_.time.dt ? *scene_.time.dt : factor * rayleigh_time_;
  if (!(dt_ > 0.0) || !std::isfinite(dt_)) {
    throw InputError(
        fmt::format("{}: time step must be positive, got {} s (time.dt or "
                    "time.dt_factor)",
                    scene_label(scene_), dt_));
  }
  const TimeStepLimit limit = time_step_limit(scene_, impl_->model, r_min);
  if (dt_ > limit.seconds() && !options.allow_unsafe_dt) {
    throw InputError(fmt::format(
        "{}: time.dt = {:.6g} s is above the stability limit of {} {} ({:.6g} s; one is {:.6g} "
        "s); use a smaller dt or --unsafe-dt",
        scene_label(scene_), dt_, limit.factor, limit.unit, limit.seconds(), limit.reference));
  }
}

SearchTuning Simulation::search_tuning() const {
  return {scene_.performance.verlet_skin};
}

void Simulation::use_search(std::unique_ptr<ContactSearch> search) {
  search_ = std::move(search);
  impl_->verlet = dynamic_cast<VerletListSearch*>(search_.get());
}

SearchInput Simulation::search_input() const {
  SearchInput in;
  in.position = particles_.position;
  in.radius = particles_.radius;
  // The composed law's interaction range (0 for a dry law): every method lists the pairs up to it.
  in.margin = impl_->model.max_pair_range();
  if (impl_->drum.periodic()) in.period_z = impl_->drum.depth();
  // A Verlet list measures the moves that close its skin in the drum's frame (a bed turning
  // with the drum stands still there); the pairs it lists do not depend on it.
  in.frame_angle = drum_angle_;
  return in;
}

std::span<const IndexPair> Simulation::computed_pairs(std::span<const IndexPair> found) {
  if (ghost_.empty()) return found;
  std::vector<IndexPair>& kept = impl_->computed;
  kept.clear();
  for (const IndexPair& q : found) {
    if (ghost_[q.i] == 0 || ghost_[q.j] == 0) kept.push_back(q);
  }
  return kept;
}

void Simulation::compute_forces(double history_dt, bool count) {
  const auto t0 = Clock::now();
  const SearchInput in = search_input();
  ContactList& contacts = impl_->contacts;
  try {
    if (impl_->verlet != nullptr) {
      // The contact list is the Verlet list itself: it changes only when the list is rebuilt.
      if (impl_->verlet->refresh(in, impl_->moved)) {
        contacts.update(computed_pairs(impl_->verlet->list()), particles_.size());
      }
    } else {
      search_->find_pairs(in, impl_->pairs);
      contacts.update(computed_pairs(impl_->pairs), particles_.size());
    }
  } catch (const InputError& e) {
    if (!count) throw;  // initial state: the input is at fault
    throw unstable_error(steps_ + 1, time_ + dt_,
                         fmt::format("contact search failed: {}; try a smaller {}", e.what(),
                                     time_step_key(dt_, rayleigh_time_)));
  }
  const auto t1 = Clock::now();
  if (!impl_->forces_cleared) particles_.clear_forces();
  impl_->forces_cleared = false;
  const double period = impl_->drum.period();
  if (!impl_->liquid_reserve.empty()) {
    seed_bridges(impl_->model.cohesive_parts(), particles_, contacts, period,
                 impl_->liquid_reserve);
  }
  const bool replay = replays_bridge_events();
  const std::size_t touching = impl_->model.add_pair_forces_parallel(
      particles_, contacts, impl_->pair_buffers, period, dt_, history_dt, replay);
  if (replay) replay_bridge_events();
  impl_->model.add_pair_forces_ordered(particles_, contacts, impl_->pair_buffers, period,
                                       history_dt, replay ? &impl_->bridge_replay : nullptr);
  if (impl_->verlet != nullptr) impl_->verlet->record_found(touching);
  const auto t2 = Clock::now();
  // Only the particles near the wall: the reach is the Verlet skin, for every search method, on
  // top of the wall range of the composed law (0 for a dry law).
  if (impl_->wall_reach < 0.0) {
    impl_->wall_reach =
        impl_->model.wall_range() + scene_.performance.verlet_skin * particles_.min_radius();
  }
  impl_->walls.refresh(particles_, impl_->drum, impl_->wall_reach, impl_->wall_history,
                       impl_->moved);
  impl_->moved = 0.0;
  std::size_t wall_contacts =
      impl_->model.add_wall_forces(particles_, impl_->walls.list(), impl_->drum, omega_,
                                   impl_->wall_history, dt_, history_dt, impl_->walls.parts());
  if (!impl_->meshes.empty()) {
    // The drum's angle where the particles now stand: a step's forces come after its drift.
    wall_contacts += impl_->model.add_mesh_forces(
        particles_, impl_->meshes, drum_angle_ + omega_ * history_dt, omega_, dt_, history_dt);
  }
  const auto t3 = Clock::now();
  if (count) {
    const SearchCounters& c = search_->counters();
    search_totals_.cells_visited += c.cells_visited;
    search_totals_.pairs_tested += c.pairs_tested;
    search_totals_.pairs_found += c.pairs_found;
    search_totals_.cells_total = c.cells_total;  // grid size of the latest step, not a sum
    timers_.search += seconds_between(t0, t1);
    timers_.forces += seconds_between(t1, t2);
    timers_.walls += seconds_between(t2, t3);
    work_.listed_pairs += contacts.size();
    work_.touching_pairs += touching;
    work_.wall_candidates += impl_->walls.list().size();
    work_.wall_contacts += wall_contacts;
  }
}

bool Simulation::replays_bridge_events() const {
  const LiquidBridge* bridge = impl_->model.part<LiquidBridge>();
  return domain_ != nullptr && domain_->bridge_events() != nullptr && bridge != nullptr &&
         bridge->moves_films();
}

void Simulation::replay_bridge_events() {
  // Collective: every rank of a wet decomposed run calls it at every force evaluation, with or
  // without events, between the cohesive parts' parallel pass and their ordered pass.
  const std::vector<double>* film = particles_.find_array(kLiquidFilmArray);
  if (film == nullptr) throw std::logic_error("bridge-event replay without a film array");
  domain_->bridge_events()->replay(*impl_->model.part<LiquidBridge>(),
                                   impl_->pair_buffers.cohesion.events, film->data(),
                                   impl_->bridge_replay);
}

Vec3 Simulation::body_acceleration_at(double angle) const {
  const DrumOrbit& o = scene_.drum.orbit;
  if (!o.active()) return gravity_;
  const double w2r = carrier_omega_ * carrier_omega_ * o.radius;
  return gravity_ + Vec3(w2r * std::cos(angle), w2r * std::sin(angle), 0.0);
}

Vec3 Simulation::carrier_offset() const {
  const double r = scene_.drum.orbit.radius;
  return Vec3(r * std::cos(carrier_angle_), r * std::sin(carrier_angle_), 0.0);
}

Vec3 Simulation::carrier_velocity() const {
  const double v = carrier_omega_ * scene_.drum.orbit.radius;
  return Vec3(-v * std::sin(carrier_angle_), v * std::cos(carrier_angle_), 0.0);
}

void Simulation::set_carrier_running(bool running) {
  carrier_omega_ = running && scene_.drum.orbit.active() ? scene_.drum.orbit.omega : 0.0;
}

void Simulation::kick(double h, const Vec3& g) {
  Particles& p = particles_;
  const std::size_t n = p.size();
  const bool rotation = impl_->model.uses_rotation();
  const std::uint8_t* ghost = ghost_.empty() ? nullptr : ghost_.data();
#pragma omp parallel
  deal_ranges(impl_->integration_blocks, n, kIntegrationBlock, [&](std::size_t b, std::size_t e) {
    std::size_t i = b;
#if defined(__AVX2__) && defined(__FMA__)
    if (ghost == nullptr) {  // four particles at a time (integration_lanes.hpp), the same bits
      const __m256d hv = _mm256_set1_pd(h);
      const Spread4 gv = repeat_vector(g.x(), g.y(), g.z());
      for (; i + 4 <= e; i += 4) {
        kick_velocity4(p.velocity[i].data(), p.force[i].data(), &p.inv_mass[i], hv, gv);
        if (rotation) kick_spin4(p.omega[i].data(), p.torque[i].data(), &p.inv_inertia[i], hv);
      }
    }
#endif
    for (; i < e; ++i) {
      if (ghost != nullptr && ghost[i] != 0) continue;  // integrated by its owner
      p.velocity[i] += h * (p.inv_mass[i] * p.force[i] + g);
      if (rotation) p.omega[i] += (h * p.inv_inertia[i]) * p.torque[i];
    }
  });
}

double Simulation::kick_drift(double h, const Vec3& g) {
  // The half kick and the drift in one pass over the particles (each particle's update reads only
  // its own data), which also clears the forces for the coming evaluation: three passes in one.
  Particles& p = particles_;
  const std::size_t n = p.size();
  const bool rotation = impl_->model.uses_rotation();
  const bool periodic = impl_->drum.periodic();
  // The largest speed and coordinate, for the bound on this drift's displacements.
  double v2max = 0.0, xmax = 0.0;
  int non_finite = 0;
  const std::uint8_t* ghost = ghost_.empty() ? nullptr : ghost_.data();
#pragma omp parallel reduction(max : v2max, xmax) reduction(| : non_finite)
  deal_ranges(impl_->integration_blocks, n, kIntegrationBlock, [&](std::size_t b, std::size_t e) {
    std::size_t i = b;
#if defined(__AVX2__) && defined(__FMA__)
    if (ghost == nullptr) {  // four particles at a time (integration_lanes.hpp), the same bits
      const __m256d hv = _mm256_set1_pd(h);
      const __m256d dt = _mm256_set1_pd(dt_);
      const Spread4 gv = repeat_vector(g.x(), g.y(), g.z());
      __m256d abs_max = _mm256_setzero_pd();
      for (; i + 4 <= e; i += 4) {
        kick_velocity4(p.velocity[i].data(), p.force[i].data(), &p.inv_mass[i], hv, gv);
        if (rotation) kick_spin4(p.omega[i].data(), p.torque[i].data(), &p.inv_inertia[i], hv);
        zero12(p.force[i].data());
        zero12(p.torque[i].data());
        if (periodic) {
          drift4(p.position[i].data(), p.velocity[i].data(), dt, abs_max);
          for (std::size_t q = i; q < i + 4; ++q) {
            p.position[q].z() = impl_->drum.wrap_z(p.position[q].z());
            xmax = std::max(xmax, p.position[q].cwiseAbs().maxCoeff());
          }
        } else {
          abs_max = drift4(p.position[i].data(), p.velocity[i].data(), dt, abs_max);
        }
        for (std::size_t q = i; q < i + 4; ++q) {
          const double v2 = p.velocity[q].squaredNorm();
          non_finite |= !std::isfinite(v2);
          v2max = std::max(v2max, v2);
        }
      }
      xmax = std::max(xmax, max_lane(abs_max));
    }
#endif
    for (; i < e; ++i) {
      if (ghost != nullptr && ghost[i] != 0) {  // integrated by its owner; its force is discarded
        p.force[i].setZero();
        p.torque[i].setZero();
        continue;
      }
      p.velocity[i] += h * (p.inv_mass[i] * p.force[i] + g);
      if (rotation) p.omega[i] += (h * p.inv_inertia[i]) * p.torque[i];
      p.force[i].setZero();
      p.torque[i].setZero();
      const double v2 = p.velocity[i].squaredNorm();
      p.position[i] += dt_ * p.velocity[i];
      if (periodic) p.position[i].z() = impl_->drum.wrap_z(p.position[i].z());
      non_finite |= !std::isfinite(v2);
      v2max = std::max(v2max, v2);
      xmax = std::max(xmax, p.position[i].cwiseAbs().maxCoeff());
    }
  });
  impl_->forces_cleared = true;
  if (domain_ != nullptr) {  // every rank's bound: the ghosts moved as far as their owners saw
    double m[3] = {v2max, xmax, static_cast<double>(non_finite)};
    domain_->max(m);
    v2max = m[0];
    xmax = m[1];
    non_finite = m[2] > 0.0 ? 1 : 0;
  }
  // |x_new - x_old| <= dt |v|, plus the round-off of the sum (a few ulps of the coordinates) and
  // of the periodic wrap (of the period).
  const double period = impl_->drum.period();
  const double bound = dt_ * std::sqrt(v2max) * (1.0 + 1e-12) +
                       8.0 * std::numeric_limits<double>::epsilon() * (xmax + period);
  const double moved =
      non_finite != 0 || !std::isfinite(xmax) ? std::numeric_limits<double>::infinity() : bound;
  impl_->moved += moved;
  return moved;
}

void Simulation::reorder_particles() {
  if (particles_.size() < 2) return;
  ReorderBuffers& b = impl_->reorder;
  morton_order(particles_.position, 2.0 * particles_.max_radius(), b);
  apply_reorder();
}

void Simulation::permute_particles(std::span<const Index> order,
                                   std::span<const std::uint64_t> row_keys) {
  ReorderBuffers& b = impl_->reorder;
  b.order.assign(order.begin(), order.end());
  b.new_index.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) b.new_index[order[k]] = static_cast<Index>(k);
  apply_reorder();
  if (!ghost_.empty()) {
    std::vector<std::uint8_t> scratch;
    apply_order(ghost_, b.order, scratch);
  }
  impl_->contacts.set_row_keys(row_keys);
}

void Simulation::apply_reorder() {
  ReorderBuffers& b = impl_->reorder;
  particles_.reorder(b.order, b);
  apply_order(impl_->wall_history, b.order, impl_->wall_scratch);
  impl_->contacts.renumber(b.new_index);
  impl_->walls.renumber(b.order, b.new_index);
  if (impl_->verlet != nullptr) impl_->verlet->renumber(b.order, b.new_index);
}

void Simulation::step() {
  // Velocity Verlet: half kick with the forces of the current positions, drift, new forces,
  // half kick. Spheres need no orientation, so rotation is the same scheme on omega.
  const std::uint64_t sort_every = scene_.performance.sort_every;
  if (sort_every > 0 && steps_ > 0 && steps_ % sort_every == 0) {
    const auto r0 = Clock::now();
    if (domain_ != nullptr) {
      domain_->reorder(*this);
    } else {
      reorder_particles();
    }
    timers_.reorder += seconds_between(r0, Clock::now());
    ++work_.reorders;
  }
  const auto t0 = Clock::now();
  // The body acceleration at the step's start and at its end (the carrier turns in between).
  const double moved = kick_drift(0.5 * dt_, body_acceleration_at(carrier_angle_));
  if (domain_ != nullptr) domain_->refresh_ghosts(*this, moved);
  const auto t1 = Clock::now();
  compute_forces(dt_, true);
  const auto t2 = Clock::now();
  kick(0.5 * dt_, body_acceleration_at(carrier_angle_ + carrier_omega_ * dt_));
  const auto t3 = Clock::now();
  timers_.integration += seconds_between(t0, t1) + seconds_between(t2, t3);
  work_.particles += particles_.size();
  if (impl_->spray) {
    // Droplets fly over [time, time + dt] against the bed at the step's end; what they bring to
    // the films forms bridges from the next step on.
    std::vector<double>& film = *particles_.find_array(kLiquidFilmArray);
    impl_->spray->advance(time_, dt_, particles_.position, particles_.radius, particles_.id, film,
                          drum_angle_ + omega_ * dt_);
    timers_.spray += seconds_between(t3, Clock::now());
  }
  time_ += dt_;
  drum_angle_ += omega_ * dt_;
  carrier_angle_ += carrier_omega_ * dt_;
  ++steps_;
}

void Simulation::advance(std::uint64_t n) {
  const std::uint64_t every = scene_.output.diagnostics_every;
  for (std::uint64_t k = 0; k < n; ++k) {
    step();
    if (every > 0 && steps_ % every == 0) check_stability();
  }
  check_stability();
}

void Simulation::set_search_method(std::string_view name) {
  // make_search throws before anything is replaced if the name is unknown.
  use_search(make_search(name, search_tuning()));
  scene_.search_method = std::string(name);
}

void Simulation::replace_local(SimulationState& state, std::vector<std::uint8_t> ghost,
                               std::span<const std::uint64_t> row_keys) {
  std::swap(particles_, state.particles);
  ghost_ = std::move(ghost);
  ContactList& c = impl_->contacts;
  c.assign(state.contact_row_start, state.contact_col, state.contact_history, state.contact_state);
  c.set_row_keys(row_keys);
  std::swap(impl_->wall_history, state.wall_history);
  use_search(make_search(scene_.search_method, search_tuning()));  // a fresh list
  impl_->walls.invalidate();
  impl_->moved = std::numeric_limits<double>::infinity();
  impl_->forces_cleared = false;
}

void Simulation::set_domain(DomainHooks* domain) {
  if (domain != nullptr && impl_->spray) {
    throw InputError("[[spray]]: not on a decomposed (MPI) run yet; run the scene with drumlab");
  }
  domain_ = domain;
}

const DropletCloud* Simulation::spray() const {
  return impl_->spray.get();
}

void Simulation::set_drum_omega(double omega) {
  if (!std::isfinite(omega)) throw InputError("drum angular velocity must be finite");
  omega_ = omega;
}

Diagnostics Simulation::diagnostics() const {
  const Particles& p = particles_;
  const Drum& drum = impl_->drum;
  const ContactModel& model = impl_->model;
  const double tol = kOutsideTolerance * drum.radius();
  Diagnostics d;
  const Vec3 carrier = carrier_velocity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (is_ghost(i)) continue;  // its owner counts it
    const Vec3& x = p.position[i];
    d.kinetic_energy += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
    d.lab_kinetic_energy += 0.5 * p.mass[i] * (p.velocity[i] + carrier).squaredNorm();
    d.rotational_energy += 0.5 * p.omega[i].squaredNorm() / p.inv_inertia[i];
    d.potential_energy -= p.mass[i] * gravity_.dot(x);
    if (!x.allFinite() || !p.velocity[i].allFinite() || !p.omega[i].allFinite()) {
      ++d.non_finite;
      continue;
    }
    if (!drum.contains_centre(x, tol)) ++d.outside_drum;
    for (std::size_t part = 0; part < kWallParts; ++part) {
      const WallContact c = drum.contact(static_cast<WallPart>(part), x, p.radius[i]);
      if (c.overlap <= 0.0) continue;
      ++d.wall_contacts;
      d.elastic_energy += model.wall_elastic_energy(c.overlap, p.radius[i]);
      if (c.overlap / p.radius[i] > d.max_overlap_ratio) {
        d.max_overlap_ratio = c.overlap / p.radius[i];
        d.max_overlap_site = wall_site(p, i, static_cast<WallPart>(part), c, omega_);
      }
    }
  }
  if (!impl_->meshes.empty()) add_mesh_diagnostics(d);
  const ContactList& contacts = impl_->contacts;
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const double period = drum.period();
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    if (is_ghost(i)) continue;  // the pair is counted by the owner of i, its first particle
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const Index j = col[k];
      const Vec3 dx = nearest_image(p.position[i], p.position[j], period);
      const double delta = p.radius[i] + p.radius[j] - dx.norm();
      if (!(delta > 0.0)) continue;
      ++d.contacts;
      const double r_eff = p.radius[i] * p.radius[j] / (p.radius[i] + p.radius[j]);
      d.elastic_energy += model.pair_elastic_energy(delta, r_eff);
      if (delta / std::min(p.radius[i], p.radius[j]) > d.max_overlap_ratio) {
        d.max_overlap_ratio = delta / std::min(p.radius[i], p.radius[j]);
        d.max_overlap_site = pair_site(p, i, j, dx);
      }
    }
  }
  const LiquidTotals liquid = this->liquid();
  d.bridges = liquid.bridge_count;
  d.wall_bridges = liquid.wall_bridge_count;
  d.liquid_volume = liquid.total();
  if (domain_ != nullptr) reduce_diagnostics(*domain_, d);
  return d;
}

void Simulation::add_mesh_diagnostics(Diagnostics& d) const {
  const Particles& p = particles_;
  const MeshWallSet& meshes = impl_->meshes;
  const double c = std::cos(drum_angle_), s = std::sin(drum_angle_);
  MeshWallSet::Scratch scratch;
  std::vector<MeshContact> hits;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (is_ghost(i) || !p.position[i].allFinite()) continue;
    meshes.contacts(p.position[i], p.radius[i], c, s, scratch, hits);
    for (const MeshContact& h : hits) {
      ++d.wall_contacts;
      d.elastic_energy += impl_->model.mesh_elastic_energy(h.wall, h.overlap, p.radius[i]);
      if (h.overlap / p.radius[i] > d.max_overlap_ratio) {
        d.max_overlap_ratio = h.overlap / p.radius[i];
        const bool turns = meshes.wall(h.wall).attach == MeshAttach::drum;
        d.max_overlap_site = mesh_site(p, i, h.wall, h.normal, h.overlap,
                                       turns ? Drum::wall_velocity(h.point, omega_) : Vec3::Zero());
      }
    }
  }
}

void Simulation::check_stability() const {
  const Diagnostics d = diagnostics();
  const auto fail = [&](const std::string& why) { throw unstable_error(steps_, time_, why); };
  if (d.non_finite > 0) {
    fail(fmt::format("{} particle(s) with non-finite position or velocity; try a smaller {}",
                     d.non_finite, time_step_key(dt_, rayleigh_time_)));
  }
  if (d.outside_drum > 0) {
    fail(fmt::format("{} particle centre(s) outside the drum; try a smaller {}", d.outside_drum,
                     time_step_key(dt_, rayleigh_time_)));
  }
  if (d.max_overlap_ratio > scene_.time.max_overlap) {
    fail(overlap_reason(d.max_overlap_site, d.max_overlap_ratio, scene_.time.max_overlap, dt_,
                        rayleigh_time_));
  }
}

}  // namespace drumlab
