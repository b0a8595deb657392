#pragma once
// Composes the contact of a scene from its parts: a normal law (Hertz or linear spring-dashpot),
// optionally the Mindlin tangential spring with history (only if friction > 0) and optionally
// rolling resistance (only if rolling_friction > 0), separately for particle-particle and
// particle-wall contacts. The choice is made here, once, at run time; the pair and wall loops in
// contact_model.cpp are templates over <normal law, tangential?, rolling?> so the chosen law
// inlines and a scene without friction does no tangential or rotational work.
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "engine/block_dealer.hpp"
#include "engine/contact/bond.hpp"
#include "engine/contact/cohesion_loops.hpp"
#include "engine/contact/cohesive_laws.hpp"
#include "engine/contact/contact_history.hpp"
#include "engine/contact/hertz_mindlin.hpp"
#include "engine/contact/linear_spring_dashpot.hpp"
#include "engine/contact/linear_viscoelastic.hpp"
#include "engine/contact/rolling_resistance.hpp"
#include "engine/contact/rolling_spring.hpp"
#include "engine/drum.hpp"
#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// One composed contact law. Tangential/rolling parts are only used when the flags say so. The
/// model keeps ContactLaw<NormalVariant> (the normal law chosen at run time); the force loops get
/// ContactLaw<HertzNormal>, ContactLaw<LinearSpringDashpot> or ContactLaw<LinearViscoelastic>, so
/// the chosen law inlines.
template <class Normal>
struct ContactLaw {
  Normal normal;
  MindlinTangential tangential;
  RollingResistance rolling;
  RollingSpring rolling_spring;  ///< used instead of `rolling` by RollingKind::spring
};

/// The rolling part a force loop is compiled with: none, RollingResistance (constant torque) or
/// RollingSpring (spring, dashpot, Coulomb limit; keeps xi_r per contact).
enum class RollingKind : std::uint8_t { none, torque, spring };
constexpr bool rolls(RollingKind r) {
  return r != RollingKind::none;
}

using NormalVariant = std::variant<HertzNormal, LinearSpringDashpot, LinearViscoelastic>;

/// The law of a triangle wall ([[wall.mesh]], [[wall.lifters]]): the wall law with the mesh's
/// own material, and which parts it has.
struct MeshLaw {
  ContactLaw<NormalVariant> law;
  bool tangential = false;
  bool rolling = false;
};

class MeshWallSet;

/// A particle-particle contact (i < j) with the force on i (N).
struct ContactForce {
  Index i;
  Index j;
  Vec3 force;
};

/// Tangential displacement of each particle against each wall part (cylinder, low cap, high cap).
using WallHistory = std::vector<std::array<Vec3, kWallParts>>;

/// Scratch of the pair loop, reused every step, for the contacts whose partner lies in another
/// block of rows (see the pair loop). One thread: their partner shares summed per particle
/// (cross_force, cross_torque). Several threads: the partner's share (force on i, torque on j) of
/// each such overlapping contact, packed per block, and for each listed pair k the slot that holds
/// it (the last slot, zeros, for a pair that does not overlap).

struct PairForceBuffers {
  std::vector<Vec3> cross_force;
  std::vector<Vec3> cross_torque;
  std::vector<std::uint32_t> slot;
  std::vector<Vec3> force;
  std::vector<Vec3> torque_j;
  BlockDealer blocks;        ///< deals the blocks of rows to the threads (several threads)
  CohesionBuffers cohesion;  ///< the cohesive parts' pass (a scene with [liquid] or [cohesion])
};

class ContactModel {
 public:
  /// Particle-particle: scene.material with itself. Particle-wall: E*, G* from scene.material
  /// combined with scene.wall; restitution, friction and rolling friction from scene.wall;
  /// R* = r, m* = m. Throws InputError for unusable parameters.
  explicit ContactModel(const SceneConfig& scene);

  bool pair_tangential() const { return pair_tangential_; }
  bool pair_rolling() const { return pair_rolling_; }
  /// Whether the rolling resistance is the spring (`[contact] rolling = "spring"`): a pair keeps
  /// xi_r in the last kRollingStateSize scalars of its contact state, a particle one per wall
  /// part in kWallRollingArrays.
  bool pair_rolling_spring() const { return pair_rolling_ && spring_; }
  bool wall_rolling_spring() const { return wall_rolling_ && spring_; }
  bool wall_tangential() const { return wall_tangential_; }
  bool wall_rolling() const { return wall_rolling_; }
  /// Interaction range of the composed particle-particle law (m): the largest surface gap
  /// |x_i - x_j| - r_i - r_j at which some part still acts on a pair of size classes a, b (0 for
  /// a dry law: contact only). The search margin is max_pair_range(), so every method lists the
  /// pairs a part may act on (a Verlet list adds its skin on top).
  double pair_range(std::uint8_t a, std::uint8_t b) const;
  double max_pair_range() const { return pair_range_; }
  /// The same for particle-wall contacts (m): the wall-candidate list reaches this much further
  /// (the rupture distance of a wall bridge of the largest volume; 0 without wall bridges).
  double wall_range() const { return cohesive_.wall_range(); }
  /// Scalars the composed law keeps per particle-particle contact (ContactList::set_state_size):
  /// the sum over its cohesive parts (from offset 0), then the rolling spring's xi_r; 0 for a dry
  /// law without the spring.
  std::size_t pair_state_size() const {
    return cohesive_.state_size() + (pair_rolling_spring() ? kRollingStateSize : 0);
  }
  /// The per-particle arrays the composed law keeps (the cohesive parts' films and wall bridges,
  /// the wall rolling springs), each once; `wall_parts`: 1 with periodic ends, else kWallParts.
  std::vector<std::string_view> particle_arrays(std::size_t wall_parts) const;
  /// The cohesive part Law (cohesive_laws.hpp) if the scene has it, e.g. part<LiquidBridge>()
  /// with [liquid], part<SjkrCohesion>() with [cohesion]; else nullptr.
  template <class Law>
  const Law* part() const {
    return cohesive_.get<Law>();
  }
  /// The cohesive parts with their state offsets (none for a dry law).
  const CohesiveParts& cohesive_parts() const { return cohesive_; }
  /// True if any contact can apply a torque (else rotation need not be integrated).
  bool uses_rotation() const {
    return pair_tangential_ || pair_rolling_ || wall_tangential_ || wall_rolling_ || mesh_torque_;
  }

  /// Adds the forces (and torques) of every contact in `contacts` to p.force / p.torque and
  /// updates the contacts' history. period > 0: minimum image along z. dt: the time step;
  /// history_dt: time since the previous evaluation (dt, or 0 for the very first one).
  /// Parallel (OpenMP) and independent of the thread count: every particle sums its contacts
  /// in the same order whatever the number of threads. A listed pair that does not overlap
  /// (e.g. a Verlet-list entry within the skin) gets no contact force and its tangential history is
  /// reset; a beyond-contact part (liquid bridge) then acts on it as long as the part's state
  /// says the interaction lives, and resets that state itself when it ends (cohesion_loops.hpp).
  /// Returns the
  /// pairs within the touching tolerance (the contacts a search with margin 0 would find).
  std::size_t add_pair_forces(Particles& p, ContactList& contacts, PairForceBuffers& buffers,
                              double period, double dt, double history_dt) const;
  /// add_pair_forces in its two halves, for a decomposed run that replays the cohesive parts'
  /// events across MPI ranks between them (Simulation::compute_forces): the contact forces and
  /// the cohesive parts' parallel pass (`list_events`: buffers.cohesion.events listed for the
  /// replay); returns the pairs within the touching tolerance.
  std::size_t add_pair_forces_parallel(Particles& p, ContactList& contacts,
                                       PairForceBuffers& buffers, double period, double dt,
                                       double history_dt, bool list_events) const;
  /// Then the cohesive parts' ordered pass (`replay`: the films each listed event sees, nullptr
  /// serially; cohesion_loops.hpp). Nothing for a dry law.
  void add_pair_forces_ordered(Particles& p, ContactList& contacts, const PairForceBuffers& buffers,
                               double period, double history_dt,
                               const BridgeEventFilms* replay) const;
  /// Adds the wall forces of the drum turning at omega (rad/s) on the particles `candidates`
  /// (increasing; the others must not touch the wall, see WallCandidates), each against the wall
  /// parts of its `near_parts` bits (WallCandidates::parts; empty: every part).
  /// history.size() == p.size(). Returns the wall contacts (overlaps) the kernel evaluated.
  std::size_t add_wall_forces(Particles& p, std::span<const Index> candidates, const Drum& drum,
                              double omega, WallHistory& history, double dt, double history_dt,
                              std::span<const std::uint8_t> near_parts = {}) const;

  /// The laws of the scene's triangle walls, in the order of engine/mesh/wall_meshes.hpp
  /// ([[wall.mesh]], then [[wall.lifters]]); empty without.
  const std::vector<MeshLaw>& mesh_laws() const { return mesh_laws_; }
  /// Adds the forces of the triangle walls `walls` (mesh_wall_set.hpp; laws as mesh_laws()) on
  /// every particle, the drum turned by `angle` (rad) at `omega` (rad/s), and advances each
  /// particle's mesh history (mesh_wall_history.hpp). Independent of the thread count: each
  /// particle adds its mesh contacts in the order of their patches. Returns the contacts.
  std::size_t add_mesh_forces(Particles& p, const MeshWallSet& walls, double angle, double omega,
                              double dt, double history_dt) const;
  /// The mesh contacts' elastic energy (J) of an overlap delta with the mesh `wall`'s law.
  double mesh_elastic_energy(std::size_t wall, double delta, double r) const;

  /// Force on i of every overlapping contact in `contacts` at the current state, without changing
  /// anything: the tangential history is used as stored (not advanced). Replaces `out` (i, j,
  /// force); contacts only touching within the search tolerance are left out.
  void pair_forces(const Particles& p, const ContactList& contacts, double period, double dt,
                   std::vector<ContactForce>& out) const;
  /// Adds the cohesive forces at the current state (live bridges' capillary force, sjkr
  /// adhesion; not the velocity-dependent viscous term) to `out` (sorted by (i, j), as
  /// pair_forces leaves it): a bridged pair apart gets its own entry. Nothing for a dry law.
  void add_cohesive_forces(const Particles& p, const ContactList& contacts, double period,
                           std::vector<ContactForce>& out) const;

  /// The cohesive links (live bridges, adhesive contacts) among `contacts` at the current state,
  /// by increasing (i, j); read-only. Replaces `out` (empty for a dry law).
  void bonds(const Particles& p, const ContactList& contacts, double period,
             std::vector<Bond>& out) const;

  /// Elastic energy of a particle-particle / particle-wall normal overlap delta (J).
  double pair_elastic_energy(double delta, double r_eff) const;
  double wall_elastic_energy(double delta, double r) const;

  const NormalVariant& pair_normal() const { return pair_.normal; }
  const NormalVariant& wall_normal() const { return wall_.normal; }

 private:
  ContactLaw<NormalVariant> pair_;
  ContactLaw<NormalVariant> wall_;
  bool pair_tangential_ = false;
  bool pair_rolling_ = false;
  bool wall_tangential_ = false;
  bool wall_rolling_ = false;
  bool spring_ = false;  ///< RollingLaw::spring
  CohesiveParts cohesive_;
  double pair_range_ = 0.0;
  std::size_t pair_block_rows_ = 0;  ///< performance.pair_block_rows
  std::vector<MeshLaw> mesh_laws_;
  bool mesh_torque_ = false;  ///< some mesh law has a tangential or rolling part
  /// Deals the wall loop's tasks to the threads: scratch of one call at a time (a model belongs
  /// to one simulation), hence mutable in add_wall_forces.
  mutable BlockDealer wall_blocks_;
};

}  // namespace drumlab
