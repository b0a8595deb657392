#pragma once
// Shared by the render tests: small scenes built without files, and pixel statistics.
#include <cmath>
#include <cstdlib>

#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"
#include "render/offscreen_context.hpp"

namespace drumlab::test {

/// A closed drum (D = 0.3 m, H = 0.05 m) at rest, no gravity, search m1, one class of radius r.
inline SceneConfig small_drum_scene(double r = 0.01) {
  SceneConfig s;
  s.name = "render_test";
  s.search_method = "m1";
  s.gravity = Vec3::Zero();
  s.classes = {ParticleClass{"grain", r, 1.0}};
  s.material = Material{2500.0, 5e6, 0.3, 0.5, 0.0, 0.0};
  s.wall = s.material;
  s.contact.normal = NormalLaw::hertz;
  s.drum = DrumConfig{0.3, 0.05, 0.0, 0.0, DrumEnds::caps, {}};
  s.output.diagnostics_every = 1000;
  return s;
}

/// Largest difference of one channel between a pixel and an RGB colour in [0, 1].
inline int color_distance(const render::Image& img, int x, int y, const double* rgb) {
  const auto px = img.pixel(x, y);
  int d = 0;
  for (int c = 0; c < 3; ++c) {
    d = std::max(d,
                 std::abs(static_cast<int>(px[c]) - static_cast<int>(std::lround(255.0 * rgb[c]))));
  }
  return d;
}

/// Share of pixels that differ from the background by more than a few levels.
inline double non_background_share(const render::Image& img, const double* background) {
  std::size_t count = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      if (color_distance(img, x, y, background) > 6) ++count;
    }
  }
  return static_cast<double>(count) / (static_cast<double>(img.width) * img.height);
}

}  // namespace drumlab::test
