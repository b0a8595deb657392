#pragma once
// A scene in the DEM vocabulary, as read from scenes/*.toml. Plain data; validated by load_scene.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/mesh_wall_config.hpp"
#include "engine/scene/size_distribution.hpp"
#include "engine/search/verlet_skin.hpp"
#include "engine/spray/spray_config.hpp"
#include "engine/types.hpp"

namespace drumlab {

struct Material {
  double density = 2500.0;        ///< kg/m^3
  double youngs_modulus = 5e6;    ///< E, Pa
  double poisson_ratio = 0.3;     ///< nu
  double restitution = 0.5;       ///< normal coefficient of restitution e, (0, 1]
  double friction = 0.5;          ///< Coulomb sliding friction mu
  double rolling_friction = 0.0;  ///< rolling resistance coefficient mu_r (dimensionless)

  friend bool operator==(const Material&, const Material&) = default;
};

/// hertz: hertz_mindlin.hpp; linear: linear_spring_dashpot.hpp (k given, damping from e per pair);
/// linear_viscoelastic: linear_viscoelastic.hpp (k and damping from a collision time and e).
enum class NormalLaw { hertz, linear, linear_viscoelastic };

/// constant_torque: rolling_resistance.hpp (drumlab's default); spring: rolling_spring.hpp
/// (MercuryDPM's rolling spring, dashpot and Coulomb limit; needs NormalLaw::linear_viscoelastic).
enum class RollingLaw { constant_torque, spring };

/// [time] max_overlap: its default and the largest value accepted (radii of the smaller body).
/// Beyond one radius the overlap lens of a small sphere on a large one is no longer a lens.
inline constexpr double kDefaultMaxOverlap = 0.5;
/// Bounds of performance.pair_block_rows.
inline constexpr std::int64_t kMinPairBlockRows = 64;
inline constexpr std::int64_t kMaxPairBlockRows = std::int64_t{1} << 20;
inline constexpr double kMaxOverlapBound = 1.0;

struct ContactConfig {
  NormalLaw normal = NormalLaw::hertz;
  /// Normal stiffness of the linear spring-dashpot law (N/m); only used with NormalLaw::linear.
  double linear_stiffness = 0.0;
  /// NormalLaw::linear_viscoelastic only: the collision time t_c (s) and the radius (m) of the
  /// reference pair (two spheres of the material's density) that collides for exactly t_c with
  /// exactly the restitution of [material] (of [wall] for the wall's law).
  double collision_time = 0.0;
  double reference_radius = 0.0;
  /// NormalLaw::linear_viscoelastic only: k_t / k and gamma_t / gamma of the tangential spring
  /// and dashpot (MercuryDPM's drum: 2/7 each).
  double tangential_stiffness_ratio = 2.0 / 7.0;
  double tangential_damping_ratio = 2.0 / 7.0;
  /// The rolling resistance law (used where rolling_friction > 0); with RollingLaw::spring,
  /// k_r / k and gamma_r / gamma of the normal law's k and gamma (MercuryDPM's drum: 2/7 each).
  RollingLaw rolling = RollingLaw::constant_torque;
  double rolling_stiffness_ratio = 2.0 / 7.0;
  double rolling_damping_ratio = 2.0 / 7.0;

  friend bool operator==(const ContactConfig&, const ContactConfig&) = default;
};

enum class DrumEnds { caps, periodic };

/// [drum.orbit]: a planetary granulator's carrier. The drum's axis (z) orbits a central axis
/// parallel to it at distance `radius`, at the carrier's rate `omega` (rad/s, positive about +z).
/// The engine works in the frame that translates with the drum's centre c(t) without turning:
/// every particle feels the uniform extra acceleration -c''(t) = omega^2 c(t) (c from the central
/// axis to the drum's centre), and the drum's wall turns in that frame at [drum] omega, its
/// absolute rate. `speed_ratio` k, when given, sets that rate as omega_drum = omega (1 + k): k is
/// the drum's rate relative to the carrier arm over the arm's rate (the planetary-mill convention;
/// k = -1: the drum does not turn in the translating frame). Inactive with radius 0.
struct DrumOrbit {
  double radius = 0.0;                ///< R_o, m; 0: no orbit
  double omega = 0.0;                 ///< Omega, rad/s
  double phase = 0.0;                 ///< the carrier's angle at t = 0, rad (c along +x at 0)
  std::optional<double> speed_ratio;  ///< k (the scene gave [drum.orbit] speed_ratio)

  bool active() const { return radius != 0.0; }
  friend bool operator==(const DrumOrbit&, const DrumOrbit&) = default;
};

/// The drum in its own frame: axis along z, centre line through x = y = 0, ends at z = 0 and
/// z = depth. A tilted drum is simulated in this frame with gravity rotated accordingly.
struct DrumConfig {
  double diameter = 0.9;  ///< D, m
  double depth = 0.15;    ///< H, m
  double omega = 1.0;     ///< angular velocity about +z, rad/s
  double tilt = 0.0;      ///< tilt of the axis from horizontal, rad (axis descends towards +z)
  DrumEnds ends = DrumEnds::caps;
  DrumOrbit orbit;  ///< [drum.orbit] (planetary); inactive by default

  friend bool operator==(const DrumConfig&, const DrumConfig&) = default;
};

/// One [[particles]] table: a size class of one radius or of a size distribution
/// (engine/scene/size_distribution.hpp). The fields are the scene's keys; size() is the value type
/// that every reader of a class's radii goes through.
struct ParticleClass {
  std::string name;
  /// m: the one radius, or the mean radius of a normal or lognormal class; 0 for a table
  double radius = 0.0;
  double volume_fraction = 1.0;  ///< share of the total solid volume, sums to 1 over classes
  SizeKind distribution = SizeKind::single;
  double radius_sigma = 0.0;           ///< m, standard deviation of the radius (normal, lognormal)
  double truncate = kDefaultTruncate;  ///< standard deviations kept either side (normal, lognormal)
  std::vector<double> radii = {};      ///< m (table)
  std::vector<double> shares = {};     ///< number shares of `radii`, any positive scale (table)
  /// liquid / solid volume of this class's particles at the start, in place of
  /// [liquid].liquid_content (a wet seed among dry fines); unset: the [liquid] value
  std::optional<double> liquid_content = {};

  SizeDistribution size() const;
  double min_radius() const { return size().min_radius(); }
  double max_radius() const { return size().max_radius(); }
  double mean_radius() const { return size().mean_radius(); }
  bool polydisperse() const { return distribution != SizeKind::single; }

  friend bool operator==(const ParticleClass&, const ParticleClass&) = default;
};

enum class FillKind {
  random,         ///< random loose fill of the lower drum, no overlaps, then settle
  paper_packing,  ///< the paper's static cubic packing in a box (contact counting only)
  file,           ///< the user's own packing from a CSV (x,y,z,r[,vx,vy,vz]), then settle
};

struct FillConfig {
  FillKind kind = FillKind::random;
  std::size_t count = 0;              ///< total particles (random fill), split by volume fraction
  double volume_fraction = 0.35;      ///< solid fraction of the random fill region
  std::uint64_t seed = 1;             ///< random fill seed
  double settle_time = 0.5;           ///< s of settling with the drum at rest before it turns
  Vec3 box = Vec3(1.85, 1.80, 0.15);  ///< paper packing box [0, box), m
  std::filesystem::path file;         ///< file fill: the CSV, resolved against the scene's folder

  friend bool operator==(const FillConfig&, const FillConfig&) = default;
};

struct TimeConfig {
  std::optional<double> dt;        ///< explicit time step (s); otherwise dt_factor * Rayleigh time
  double dt_factor = 0.2;          ///< fraction of the Rayleigh time of the smallest particle
  std::optional<double> duration;  ///< simulated seconds after settling
  std::optional<double> revolutions;
  /// Largest overlap a healthy run may show, in radii of the smaller body of a contact: a larger
  /// one stops the run (UnstableError).
  double max_overlap = kDefaultMaxOverlap;

  friend bool operator==(const TimeConfig&, const TimeConfig&) = default;
};

/// Knobs that change the speed of a run, never its physics (LAMMPS: neighbor skin, atom_modify
/// sort).
struct PerformanceConfig {
  /// Verlet skin in units of the smallest radius (methods "verlet", "verlet:<grid>").
  double verlet_skin = kDefaultVerletSkin;
  /// Re-order the particles in memory along a space-filling curve every this many steps (0: never),
  /// so that neighbours sit close in memory. Trajectories do not depend on it beyond round-off
  /// of the summation order.
  std::uint64_t sort_every = 100;
  /// The pair loop's fixed blocks of rows, in particles (engine/contact/contact_model.cpp): a
  /// particle's force is summed block by block, so trajectories depend on it at round-off, never
  /// on the thread or rank count. Threads take whole blocks, so a scene needs several blocks a
  /// thread (512 keeps a 2000-particle drum on two threads); a large drum runs faster with
  /// 2048, whose particles (about 300 KB of arrays) still fit the L2 cache (app/bench/README.md).
  std::uint64_t pair_block_rows = 512;

  friend bool operator==(const PerformanceConfig&, const PerformanceConfig&) = default;
};

/// Pendular liquid bridges ([liquid]; engine/contact/liquid_bridge.hpp). Absent: a dry scene.
/// Two ways to give the liquid: `bridge_volume` (every bridge holds V, no films, no migration) or
/// `liquid_content` + `max_bridge_volume` (liquid migration: each particle carries a film, a
/// new bridge draws from the films, a ruptured one returns its liquid to them).
struct LiquidConfig {
  bool enabled = false;
  double surface_tension = 0.0;    ///< N/m, > 0
  double contact_angle_deg = 0.0;  ///< degrees, in [0, 90)
  double bridge_volume = 0.0;      ///< m^3 of every bridge (no migration); 0 with migration
  bool migration = false;          ///< liquid_content given: films and migration
  double liquid_content = 0.0;     ///< liquid volume / solid volume of each particle, >= 0
  /// Share of each particle's liquid in its film at the start, in [0, 1]; the rest forms the
  /// bridges of the contacts present at the start (none: all stays in the film).
  double film_share = 1.0;
  double max_bridge_volume = 0.0;  ///< m^3, > 0 (migration)
  /// Migration: 0 gives each particle liquid_content times its own volume; > 0 (m) gives every
  /// particle liquid_content times the volume of a sphere of this radius (MercuryDPM's drum: the
  /// same film on every particle, from the mean radius).
  double film_radius = 0.0;
  /// Migration: a new bridge of V_max draws half from each film (false) or from the two films in
  /// proportion to their volumes (true, MercuryDPM's LiquidMigrationWilletInteraction::form).
  bool proportional_draw = false;
  /// Migration: MercuryDPM's distribution coefficient c in [0, 1] (its default 1): at a rupture
  /// each particle's half goes, for the share c, to that particle's other live bridges (equal
  /// shares, each topped at max_bridge_volume with the excess to the film), the rest to its film;
  /// a particle without another bridge takes its whole half. 0: all to the films.
  double rupture_to_bridges = 0.0;
  double viscosity = 0.0;    ///< eta of the liquid, Pa s; 0: no viscous term
  double min_gap = 0.0;      ///< m, > 0 with viscosity: the viscous term's smallest gap
  bool wall_bridges = true;  ///< particle-wall bridges (R = 2 Rp)
  /// N/m; the loader sets it to surface_tension when the scene gives none (a config built in
  /// code must set it too)
  double wall_surface_tension = 0.0;
  double wall_contact_angle_deg = 0.0;  ///< degrees; the loader's default is contact_angle_deg

  friend bool operator==(const LiquidConfig&, const LiquidConfig&) = default;
};

/// Dry adhesion ([cohesion] model = "sjkr"; engine/contact/sjkr_cohesion.hpp). Absent: none.
struct CohesionConfig {
  bool enabled = false;
  double energy_density = 0.0;  ///< k_c, J/m^3 (= Pa), >= 0 (0: the part runs, adds nothing)

  friend bool operator==(const CohesionConfig&, const CohesionConfig&) = default;
};

struct OutputConfig {
  std::string directory = "out";
  std::uint64_t diagnostics_every = 1000;  ///< steps between stability checks / progress

  friend bool operator==(const OutputConfig&, const OutputConfig&) = default;
};

struct SceneConfig {
  std::string name;    ///< from the file name unless set
  std::string source;  ///< file the scene came from (for error messages)
  std::string description;
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  ///< lab frame, m/s^2
  DrumConfig drum;
  std::vector<ParticleClass> classes;
  Material material;
  Material wall;                          ///< particle-wall contact (density unused)
  std::vector<MeshWallConfig> meshes;     ///< [[wall.mesh]]: triangle walls from STL files
  std::vector<LifterWallConfig> lifters;  ///< [[wall.lifters]]: generated flights
  ContactConfig contact;
  LiquidConfig liquid;
  CohesionConfig cohesion;
  std::vector<SprayConfig> sprays;  ///< [[spray]]: nozzles of binder (engine/spray)
  FillConfig fill;
  TimeConfig time;
  std::string search_method = "m5";
  PerformanceConfig performance;
  OutputConfig output;

  /// The smallest and largest radius any class can have (a distribution's truncation bounds).
  double min_radius() const;
  double max_radius() const;
  /// True for the fills that start a dynamic run (random, file); false for the static packing.
  bool dynamic() const { return fill.kind != FillKind::paper_packing; }
  /// True if the scene has triangle walls ([[wall.mesh]] or [[wall.lifters]]).
  bool has_meshes() const { return !meshes.empty() || !lifters.empty(); }
  /// Field by field, every field including `source` (engine/scene/scene_writer.hpp writes every
  /// field but `source`; a written scene parsed under the same source name compares equal).
  friend bool operator==(const SceneConfig&, const SceneConfig&) = default;
};

/// `[output] directory` when the scene names none.
std::string default_output_directory(std::string_view scene_name);

/// The drum tilt in radians for `[drum] tilt_deg` (the loader's one conversion).
double tilt_from_degrees(double degrees);
/// The `tilt_deg` to write for a tilt in radians: the shortest decimal whose tilt_from_degrees is
/// exactly `radians` (searched a few ulps around radians * 180 / pi), or the nearest one when no
/// double maps back exactly.
double tilt_in_degrees(double radians);

/// Reads and validates a scene. Throws InputError with one line "FILE: KEY: reason".
SceneConfig load_scene(const std::filesystem::path& file);
/// Same, from text (tests); `source` names it in messages.
SceneConfig parse_scene(std::string_view toml_text, std::string_view source);

}  // namespace drumlab
