#pragma once
// A contact law seen on two bodies (`drumlab law`, and the unit tests of the laws): two spheres
// of the scene's classes (or one and the drum mantle) at prescribed positions, at rest, approach
// from a gap to a given overlap and are pulled apart past the bridge's rupture, quasi-statically.
// At every position the force is read from the ContactModel code path the simulation runs
// (add_pair_forces / add_wall_forces on a two-particle contact list or a one-particle wall
// candidate list), state and films carried from one position to the next: not a copy of the
// formulas.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/scene/scene_config.hpp"

namespace drumlab {

struct LawProbeOptions {
  std::uint8_t class_a = 0;
  std::uint8_t class_b = 0;
  bool wall = false;        ///< class_a against the drum mantle (at its lowest point)
  double overlap = -1.0;    ///< deepest overlap (m); < 0: 2 % of the smallest radius
  double start_gap = -1.0;  ///< first gap (m); < 0: 10 % of the smallest radius
  double end_gap = -1.0;    ///< last gap of the retreat (m); < 0: 1.5 x the law's range + start
  std::size_t steps = 400;  ///< positions per branch
};

struct LawSample {
  double gap = 0.0;            ///< surface gap s (m), negative: overlap
  double normal_force = 0.0;   ///< along the normal (N): > 0 repulsive, < 0 attractive
  double bridge_volume = 0.0;  ///< m^3, 0 without a bridge
  bool retreat = false;        ///< false: approach branch
};

struct LawCurve {
  std::vector<LawSample> samples;
  /// Gap of the last retreat sample that still had a bridge (m); NaN if none had one.
  double last_bridged_gap = 0.0;
  /// Gap of the first retreat sample after that without one (m); NaN if none.
  double rupture_gap = 0.0;
  /// Rupture distance the law predicts for the bridge that formed (m); NaN without one.
  double predicted_rupture = 0.0;
  std::string label;  ///< e.g. "small-large" or "small-wall"
};

/// Throws InputError for a class index out of range or a non-positive overlap.
LawCurve probe_law(const SceneConfig& scene, const LawProbeOptions& options);

}  // namespace drumlab
