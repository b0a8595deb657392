#pragma once
// A scene in the DEM vocabulary, as read from scenes/*.toml. Plain data; validated by load_scene.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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

enum class NormalLaw { hertz, linear };

struct ContactConfig {
  NormalLaw normal = NormalLaw::hertz;
  /// Normal stiffness of the linear spring-dashpot law (N/m); only used with NormalLaw::linear.
  double linear_stiffness = 0.0;

  friend bool operator==(const ContactConfig&, const ContactConfig&) = default;
};

enum class DrumEnds { caps, periodic };

/// The drum in its own frame: axis along z, centre line through x = y = 0, ends at z = 0 and
/// z = depth. A tilted drum is simulated in this frame with gravity rotated accordingly.
struct DrumConfig {
  double diameter = 0.9;  ///< D, m
  double depth = 0.15;    ///< H, m
  double omega = 1.0;     ///< angular velocity about +z, rad/s
  double tilt = 0.0;      ///< tilt of the axis from horizontal, rad (axis descends towards +z)
  DrumEnds ends = DrumEnds::caps;

  friend bool operator==(const DrumConfig&, const DrumConfig&) = default;
};

struct ParticleClass {
  std::string name;
  double radius = 0.0;           ///< m
  double volume_fraction = 1.0;  ///< share of the total solid volume, sums to 1 over classes

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

  friend bool operator==(const TimeConfig&, const TimeConfig&) = default;
};

/// Knobs that change the speed of a run, never its physics (LAMMPS: neighbor skin, atom_modify
/// sort).
struct PerformanceConfig {
  /// Verlet skin in units of the smallest radius (methods "verlet", "verlet:<grid>").
  double verlet_skin = 0.5;
  /// Re-order the particles in memory along a space-filling curve every this many steps (0: never),
  /// so that neighbours sit close in memory. Trajectories do not depend on it beyond round-off
  /// of the summation order.
  std::uint64_t sort_every = 100;

  friend bool operator==(const PerformanceConfig&, const PerformanceConfig&) = default;
};

/// Pendular liquid bridges between particles ([liquid]; engine/contact/liquid_bridge.hpp).
/// Absent: a dry scene.
struct LiquidConfig {
  bool enabled = false;
  double surface_tension = 0.0;    ///< N/m, > 0
  double contact_angle_deg = 0.0;  ///< degrees, in [0, 90)
  double bridge_volume = 0.0;      ///< m^3 of every bridge, > 0 (no liquid migration yet)

  friend bool operator==(const LiquidConfig&, const LiquidConfig&) = default;
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
  Material wall;  ///< particle-wall contact (density unused)
  ContactConfig contact;
  LiquidConfig liquid;
  FillConfig fill;
  TimeConfig time;
  std::string search_method = "m5";
  PerformanceConfig performance;
  OutputConfig output;

  double min_radius() const;
  double max_radius() const;
  /// True for the fills that start a dynamic run (random, file); false for the static packing.
  bool dynamic() const { return fill.kind != FillKind::paper_packing; }
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
