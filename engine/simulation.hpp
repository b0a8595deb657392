#pragma once
// The DEM time loop. Owns the particles, the contact search, the contact history and the drum.
// One step: search -> pair forces -> wall forces -> integrate. The step itself does no I/O;
// observers read the public state between steps (particles(), search(), counters, timers).
#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "engine/contact/bond.hpp"
#include "engine/contact/cohesion_loops.hpp"
#include "engine/parallel/domain_hooks.hpp"
#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/simulation_state.hpp"
#include "engine/stability.hpp"

namespace drumlab {

/// Wall-clock seconds spent in each phase of the step, summed since construction.
struct StepTimers {
  double search = 0.0;
  double forces = 0.0;
  double walls = 0.0;
  double integration = 0.0;
  double reorder = 0.0;  ///< re-ordering the particles in memory (every sort_every steps)
  double spray = 0.0;    ///< the binder droplets' flight and absorption (scenes with [[spray]])
  double total() const { return search + forces + walls + integration + reorder + spray; }
};

/// The work the steps did, summed since construction: what `drumlab bench roofline` multiplies by
/// the cost of each unit of work (app/bench/roofline_model.hpp).
struct StepWork {
  std::uint64_t particles = 0;        ///< particles in the step's loops (a rank's: with ghosts)
  std::uint64_t listed_pairs = 0;     ///< pairs in the contact list the force loop walked
  std::uint64_t touching_pairs = 0;   ///< of those, within the touching tolerance
  std::uint64_t wall_candidates = 0;  ///< particles in the wall-candidate list
  std::uint64_t reorders = 0;         ///< re-orderings of the particles in memory
  std::uint64_t wall_contacts = 0;    ///< wall contacts (overlaps) the wall kernel evaluated
};

/// Snapshot of physical health, computed on demand (not every step).
struct Diagnostics {
  double kinetic_energy = 0.0;     ///< translational, J
  double rotational_energy = 0.0;  ///< J
  double potential_energy = 0.0;   ///< gravitational, relative to the drum axis, J
  /// Translational kinetic energy in the lab frame (J): with [drum.orbit] the particles' speeds
  /// plus the drum centre's; else equal to kinetic_energy.
  double lab_kinetic_energy = 0.0;
  double elastic_energy = 0.0;     ///< stored in normal contacts, J
  double max_overlap_ratio = 0.0;  ///< max overlap / smaller radius over all contacts
  OverlapSite max_overlap_site;    ///< the contact with that overlap (if any)
  std::size_t outside_drum = 0;    ///< particle centres outside the drum volume
  std::size_t non_finite = 0;      ///< particles with a non-finite position or velocity
  std::size_t contacts = 0;        ///< particle-particle contacts
  std::size_t wall_contacts = 0;
  std::size_t bridges = 0;       ///< live particle-particle liquid bridges
  std::size_t wall_bridges = 0;  ///< live particle-wall liquid bridges
  double liquid_volume = 0.0;    ///< films + bridges + wall bridges, m^3 (0 for a dry scene)
};

struct SimulationOptions {
  bool allow_unsafe_dt = false;     ///< accept dt above kMaxSafeDtFactor Rayleigh times
  double dt_factor_override = 0.0;  ///< > 0 replaces the scene's dt_factor
};

class DropletCloud;
class MeshWallSet;
struct WallMesh;

class Simulation {
 public:
  /// Takes the scene's physics and the given particles (already placed by a fill).
  /// Throws InputError for an unusable configuration (dt above the Rayleigh time without
  /// allow_unsafe_dt, particles outside the drum, unknown search method).
  Simulation(const SceneConfig& scene, Particles particles, SimulationOptions options = {});
  /// Continues from a saved state (restart): the physics comes from `scene`, everything that
  /// evolves (particles incl. forces, clock, dt, drum angle and omega, search method, contact and
  /// wall history) from `state`, so the next steps are bit-identical to those of the simulation
  /// that exported it. Throws InputError if the state is inconsistent or does not fit the drum.
  Simulation(const SceneConfig& scene, SimulationState state);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Advances one time step.
  void step();
  /// Advances n steps, checking stability every scene.output.diagnostics_every steps; throws
  /// UnstableError with a one-line reason when the state goes bad.
  void advance(std::uint64_t n);

  /// Re-orders the particles in memory along a space-filling curve (cache locality); done
  /// automatically every scene.performance.sort_every steps. Storage slots change, stable ids
  /// (particles().id) and contact histories follow.
  void reorder_particles();
  /// Re-orders the particles so that slot k holds the particle now at order[k] (histories and
  /// lists follow, as for reorder_particles); `row_keys` as for replace_local (empty: serial).
  void permute_particles(std::span<const Index> order, std::span<const std::uint64_t> row_keys);
  /// Switches the contact search between steps (contact history is kept).
  void set_search_method(std::string_view name);
  /// Sets the drum's angular velocity (rad/s), e.g. 0 while settling.
  void set_drum_omega(double omega);

  /// Makes this simulation one rank's part of a decomposed run (engine/parallel/domain_hooks.hpp):
  /// global decisions through `domain`'s reductions, ghosts refreshed between drift and search,
  /// the liquid's bridge events replayed through its bridge_events() between the two passes of
  /// the cohesive parts (parallel/bridge_events.hpp).
  void set_domain(DomainHooks* domain);
  /// 1 for a ghost (another rank's particle), 0 for an owned one; empty: all owned (serial).
  /// Ghosts are neither integrated nor checked; their forces are computed and discarded.
  const std::vector<std::uint8_t>& ghost_mask() const { return ghost_; }
  bool is_ghost(std::size_t i) const { return !ghost_.empty() && ghost_[i] != 0; }
  /// The particles for the decomposition to update ghosts in (never during a step's loops).
  Particles& local_particles() { return particles_; }
  /// Replaces this rank's particles, contact list and wall history (a migration): `ghost` is the
  /// mask above, `row_keys` the serial run's slot of each particle (ContactList::set_row_keys).
  /// The search lists are rebuilt at the next evaluation.
  /// `state` gets this rank's previous particles and wall history back (to fill again at the
  /// next migration without allocating).
  void replace_local(SimulationState& state, std::vector<std::uint8_t> ghost,
                     std::span<const std::uint64_t> row_keys);

  const Particles& particles() const { return particles_; }
  /// The contact list (rows in storage slots) and the wall history, read-only: what a migration
  /// keeps of the particles that stay on their rank, without copying the state.
  const ContactList& contacts() const;
  const WallHistory& wall_history() const;
  const SceneConfig& scene() const { return scene_; }
  const ContactSearch& search() const { return *search_; }
  /// The search's input on the current state (positions, radii, margin, z period): what the step
  /// searches, and what search().visit() replays one particle's search on.
  SearchInput search_input() const;
  /// Search counters summed over all steps since construction.
  const SearchCounters& search_totals() const { return search_totals_; }
  const StepTimers& timers() const { return timers_; }
  const StepWork& work() const { return work_; }
  double time() const { return time_; }
  double dt() const { return dt_; }
  double rayleigh_time() const { return rayleigh_time_; }
  double drum_omega() const { return omega_; }
  double drum_angle() const { return drum_angle_; }
  std::uint64_t steps() const { return steps_; }
  /// Gravity in the drum frame (the lab gravity rotated by the tilt).
  const Vec3& gravity() const { return gravity_; }
  /// A planetary drum ([drum.orbit]): the carrier's angle (rad) and rate (rad/s, 0 while it
  /// stands); the drum centre's position c and velocity relative to the central axis (m, m/s);
  /// the acceleration every particle feels now, gravity + Omega^2 c (gravity without an orbit).
  double carrier_angle() const { return carrier_angle_; }
  double carrier_omega() const { return carrier_omega_; }
  Vec3 carrier_offset() const;
  Vec3 carrier_velocity() const;
  Vec3 body_acceleration() const { return body_acceleration_at(carrier_angle_); }
  /// Starts (the scene's Omega) or stops (0) the carrier, as set_drum_omega does the drum.
  void set_carrier_running(bool running);

  /// Everything the next step depends on (for checkpoints); see SimulationState.
  SimulationState state() const;
  /// The state() without copying the particles and the wall history: they are moved out, and
  /// this Simulation holds no particles afterwards (it must not step again). A decomposed run
  /// takes the whole state so from the session that built it, one copy fewer at startup.
  SimulationState take_state();
  /// Force on i of every overlapping particle-particle contact at the current state (i < j),
  /// evaluated read-only with the stored tangential history, and of every live liquid bridge or
  /// adhesive contact (their capillary / adhesive force added; a bridged pair apart has an entry
  /// of its own). Replaces `out`, by increasing (i, j).
  void contact_forces(std::vector<ContactForce>& out) const;
  /// The cohesive links (liquid bridges, adhesive contacts) at the current state, by increasing
  /// (i, j) in storage slots; replaces `out` (empty for a dry scene). See engine/contact/bond.hpp.
  void bonds(std::vector<Bond>& out) const;
  /// Liquid in films, bridges and wall bridges (m^3), with the live bridge counts; zeros for a
  /// dry scene. Films + bridges + wall bridges is conserved by every step (round-off).
  LiquidTotals liquid() const;
  /// The triangle walls ([[wall.mesh]], [[wall.lifters]]); empty without.
  const MeshWallSet& meshes() const;
  /// The same meshes (in the drum's frame at angle 0) as one immutable list that a snapshot can
  /// share with another thread (FrameSnapshot::meshes); null without.
  std::shared_ptr<const std::vector<WallMesh>> wall_meshes() const;
  /// The binder droplets and their liquid accounting of a scene with [[spray]]; null without.
  /// Films + bridges + wall bridges + airborne + lost = the scene's liquid + the sprayed.
  const DropletCloud* spray() const;
  /// Particle-particle contacts (overlap > 0) of each particle; replaces `out` (size N).
  void coordination_numbers(std::vector<std::uint32_t>& out) const;

  Diagnostics diagnostics() const;
  /// Throws UnstableError if diagnostics show non-finite values, particles outside the drum or
  /// overlaps above half a radius.
  void check_stability() const;

 private:
  /// state() into `out` (state() and take_state() share it).
  void state_into(SimulationState& out) const;
  struct Impl;
  void validate_particles();
  /// Registers the contact law's per-particle arrays (films, wall bridges, wall rolling springs:
  /// ContactModel::particle_arrays) if the scene has them and the particles do not; `fresh`: fill
  /// the films from the liquid content (else: a restart, which must bring them).
  void register_liquid_arrays(bool fresh);
  /// Creates the droplet cloud of a scene with [[spray]] (after the particles are in place).
  void make_spray();
  /// Builds the triangle walls of a scene with [[wall.mesh]] or [[wall.lifters]].
  void make_meshes();
  /// Throws InputError if the mesh history names a patch the scene's meshes do not have.
  void check_mesh_history() const;
  /// Adds the triangle walls' contacts to `d` (count, elastic energy, largest overlap).
  void add_mesh_diagnostics(Diagnostics& d) const;
  void choose_time_step(const SimulationOptions& options);
  /// The found pairs the force loop computes: all of them serially; on a rank of a decomposed
  /// run all but those of two ghosts, whose forces would be discarded and whose state no owner
  /// keeps (a pair's record travels only from a rank that owns one of its particles).
  std::span<const IndexPair> computed_pairs(std::span<const IndexPair> found);
  /// Search, contact list update, pair and wall forces. history_dt: time since the last call
  /// (0 for the initial state); count: add to the timers and search totals.
  void compute_forces(double history_dt, bool count);
  /// A decomposed run with liquid migration: this step's bridge events of every rank replayed in
  /// the serial order (DomainHooks::bridge_events(), parallel/bridge_events.hpp), so that the
  /// cohesive parts' ordered pass runs each from the films the serial run gives it. A step of
  /// compute_forces, between the two passes; replays_bridge_events() says whether it runs.
  bool replays_bridge_events() const;
  void replay_bridge_events();
  SearchTuning search_tuning() const;
  /// Makes `search` the active method (and notes whether it is a Verlet list).
  void use_search(std::unique_ptr<ContactSearch> search);
  /// Applies impl_->reorder's order and new_index to the particles, histories and lists.
  void apply_reorder();
  /// v += h (F / m + g) for every owned particle, g the body acceleration of that instant.
  void kick(double h, const Vec3& g);
  /// kick(h, g), then positions advanced by dt (the forces are cleared on the way); returns a
  /// bound on how far any particle moved (over all ranks with a domain; infinite if not finite).
  double kick_drift(double h, const Vec3& g);
  /// gravity + Omega^2 c for the carrier at angle `angle` (gravity alone without an orbit): the
  /// frame that translates with the drum's centre is accelerated by c'' = -Omega^2 c.
  Vec3 body_acceleration_at(double angle) const;

  SceneConfig scene_;
  Particles particles_;
  std::unique_ptr<ContactSearch> search_;
  std::unique_ptr<Impl> impl_;
  SearchCounters search_totals_;
  StepTimers timers_;
  StepWork work_;
  Vec3 gravity_ = Vec3::Zero();
  double carrier_angle_ = 0.0;  ///< rad ([drum.orbit])
  double carrier_omega_ = 0.0;  ///< rad/s, the carrier's current rate
  double time_ = 0.0;
  double dt_ = 0.0;
  double rayleigh_time_ = 0.0;
  double omega_ = 0.0;
  double drum_angle_ = 0.0;
  std::uint64_t steps_ = 0;
  DomainHooks* domain_ = nullptr;
  std::vector<std::uint8_t> ghost_;
};

/// Largest time step accepted without allow_unsafe_dt, in Rayleigh times of the smallest
/// particle. Measured: `drumlab stress` goes unstable at dt = 1 t_R (a Hertz impact at ~1 m/s then
/// lasts about 2 steps) and `drumlab bench accuracy` at 0.8 t_R, while 0.4-0.5 t_R run stable.
inline constexpr double kMaxSafeDtFactor = 0.5;

/// Largest time step accepted without allow_unsafe_dt for the linear normal laws (linear,
/// linear_viscoelastic), in undamped contact half-periods pi sqrt(m*/k) of the lightest pair (or
/// the lightest particle on the wall, m* = m): velocity Verlet on a lone spring diverges above
/// 2/pi = 0.64 of it; 0.2 keeps a margin of 3 for contact networks and damping (MercuryDPM's
/// drum runs 0.05 collision times of its mean pair, 0.087 of its lightest).
inline constexpr double kMaxSafeLinearDtFactor = 0.2;

/// The largest time step a scene takes without allow_unsafe_dt: `factor` times `reference` (s),
/// the Rayleigh time of the smallest particle (Hertz) or the undamped contact half-period of the
/// lightest pair or particle on the wall (the linear laws, whose stiffness E does not set).
struct TimeStepLimit {
  double factor = 0.0;
  double reference = 0.0;  ///< s
  const char* unit = "";   ///< what `reference` is, plural ("Rayleigh times")
  double seconds() const { return factor * reference; }
};
class ContactModel;
TimeStepLimit time_step_limit(const SceneConfig& scene, const ContactModel& model, double r_min);

/// m*/c (s) of the liquid bridges' viscous term for the lightest particles (radius r_min) at
/// the smallest gap, c = 6 pi eta R*^2 / min_gap: between two of them (m* = m/2, R* = r/2) and,
/// with wall bridges, at the wall (m* = m, R* = r); nullopt without a viscous term.
std::optional<double> viscous_relaxation_time(const SceneConfig& scene, double r_min);

/// Rayleigh time of a sphere (s): pi r sqrt(rho / G) / (0.1631 nu + 0.8766), G = E / (2 (1 + nu)).
double rayleigh_time(double radius, const Material& m);

}  // namespace drumlab
