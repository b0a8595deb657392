#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "engine/scene/scene_config.hpp"

namespace drumlab {

double SceneConfig::min_radius() const {
  if (classes.empty()) return 0.0;
  return std::min_element(classes.begin(), classes.end(),
                          [](const auto& a, const auto& b) { return a.radius < b.radius; })
      ->radius;
}

double SceneConfig::max_radius() const {
  if (classes.empty()) return 0.0;
  return std::max_element(classes.begin(), classes.end(),
                          [](const auto& a, const auto& b) { return a.radius < b.radius; })
      ->radius;
}

std::string default_output_directory(std::string_view scene_name) {
  return fmt::format("out/{}", scene_name);
}

double tilt_from_degrees(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

double tilt_in_degrees(double radians) {
  const double guess = radians * 180.0 / std::numbers::pi;
  // Candidates a few ulps either side of the guess; keep those that load back exactly and take
  // the one with the shortest round-trip decimal (ties: the nearest to the guess).
  double best = guess;
  std::size_t best_length = std::numeric_limits<std::size_t>::max();
  double below = guess;
  double above = guess;
  for (int k = 0; k <= 8; ++k) {
    for (const double candidate : {below, above}) {
      if (tilt_from_degrees(candidate) != radians) continue;
      const std::size_t length = fmt::format("{}", candidate).size();
      if (length < best_length) {
        best = candidate;
        best_length = length;
      }
    }
    below = std::nextafter(below, -std::numeric_limits<double>::infinity());
    above = std::nextafter(above, std::numeric_limits<double>::infinity());
  }
  return best;
}

}  // namespace drumlab
