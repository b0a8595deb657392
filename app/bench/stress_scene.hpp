#pragma once
// Small scenes and packings for the stress cases, written as the TOML/CSV a user would write.
#include <cstddef>
#include <filesystem>
#include <string>

namespace drumlab::bench {

/// A small drum scene (random fill unless fill_file is set).
struct StressScene {
  double diameter = 0.1;        ///< m
  double depth = 0.025;         ///< m
  double froude = 0.05;         ///< omega = sqrt(Fr g / R)
  double radius = 0.004;        ///< m (the small class)
  double large_radius = 0.0;    ///< m; 0: one size class only
  double large_fraction = 0.5;  ///< share of the solid volume of the large class
  double youngs_modulus = 5e6;
  double friction = 0.5;
  double rolling_friction = 0.0;
  double restitution = 0.5;
  std::size_t count = 200;
  double settle_time = 0.1;  ///< s
  double duration = 0.2;     ///< s of turning
  double dt_factor = 0.2;    ///< of the Rayleigh time
  std::size_t diagnostics_every = 50;
  std::string fill_file;  ///< if set: [fill] kind = "file"
  bool zero_gravity = false;
  std::string search = "m5";
  bool periodic = false;  ///< periodic drum ends instead of caps
  double tilt_deg = 0.0;

  double omega() const;
  std::string toml() const;
  /// e.g. "200 p, r 4 mm, Fr 0.05, E 5e6 Pa, mu 0.5"
  std::string summary() const;
};

/// A case name as a file or folder name: letters, digits, '.', '-' kept, anything else '_'.
std::string file_stem(const std::string& name);

/// Writes `text` to `file` and returns the path.
std::filesystem::path write_text(const std::filesystem::path& file, const std::string& text);

/// A simple cubic lattice of equal spheres of radius r filling the lower part of the drum of
/// `scene` (centres at least `wall_gap` x r inside the walls) with centre spacing
/// 2 r (1 - overlap / 2), so neighbours overlap by `overlap` x r; at most `max_count` particles.
/// CSV text x,y,z,r.
std::string lattice_csv(const StressScene& scene, double r, double overlap, std::size_t max_count,
                        double wall_gap = 1.0);

}  // namespace drumlab::bench
