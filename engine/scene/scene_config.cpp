#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "engine/scene/scene_config.hpp"

namespace drumlab {

SizeDistribution ParticleClass::size() const {
  switch (distribution) {
    case SizeKind::normal:
      return SizeDistribution::normal(radius, radius_sigma, truncate);
    case SizeKind::lognormal:
      return SizeDistribution::lognormal(radius, radius_sigma, truncate);
    case SizeKind::table:
      return SizeDistribution::table(radii, shares);
    case SizeKind::single:
      break;
  }
  return SizeDistribution::single(radius);
}

double SceneConfig::min_radius() const {
  if (classes.empty()) return 0.0;
  double r = std::numeric_limits<double>::infinity();
  for (const ParticleClass& c : classes) r = std::min(r, c.min_radius());
  return r;
}

double SceneConfig::max_radius() const {
  double r = 0.0;
  for (const ParticleClass& c : classes) r = std::max(r, c.max_radius());
  return r;
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
