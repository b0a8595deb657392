#include "app/cli/scene_setup.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

namespace drumlab::cli {

double froude_number(const SceneConfig& scene) {
  const double r = 0.5 * scene.drum.diameter;
  const double tilt = scene.drum.tilt;
  // Gravity across the axis: the lab gravity's component perpendicular to the tilted axis.
  const double g = scene.gravity.norm() * std::cos(tilt);
  return g > 0.0 ? scene.drum.omega * scene.drum.omega * r / g : INFINITY;
}

std::string regime_for_froude(double fr) {
  // Mellmann (2001), Powder Technol. 118: slumping < 1e-4 < rolling < 1e-2, cascading 1e-3..0.1,
  // cataracting 0.1..1, centrifuging >= 1. The rolling and cascading ranges overlap.
  if (fr < 1e-4) return "slumping";
  if (fr < 1e-3) return "rolling";
  if (fr < 1e-2) return "rolling/cascading";
  if (fr < 0.1) return "cascading";
  if (fr < 1.0) return "cataracting";
  return "centrifuging";
}

std::string shipped_scene(std::string_view file_name) {
  return (std::filesystem::path(DRUMLAB_SCENES_DIR) / file_name).string();
}

}  // namespace drumlab::cli
