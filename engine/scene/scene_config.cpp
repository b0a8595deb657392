#include <algorithm>

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

}  // namespace drumlab
