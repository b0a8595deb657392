#pragma once
// Small builders shared by the validation tests: a scene without a file, and pair observables.
#include <cmath>
#include <vector>

#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"

namespace drumlab::test {

/// A scene with one particle class (radius r), a soft Hertz material without friction, a closed
/// drum at rest, no gravity and the brute-force search. Tests change what they need.
inline SceneConfig make_scene(double r = 0.01) {
  SceneConfig s;
  s.name = "validation";
  s.search_method = "brute";
  s.gravity = Vec3::Zero();
  s.classes = {ParticleClass{"grain", r, 1.0}};
  s.material = Material{2500.0, 5e6, 0.3, 0.5, 0.0, 0.0};
  s.wall = s.material;
  s.contact.normal = NormalLaw::hertz;
  s.drum = DrumConfig{1.0, 1.0, 0.0, 0.0, DrumEnds::caps, {}};
  s.output.diagnostics_every = 1000;
  return s;
}

/// Surface overlap of particles a and b (negative when apart).
inline double overlap(const Particles& p, Index a, Index b) {
  return p.radius[a] + p.radius[b] - (p.position[a] - p.position[b]).norm();
}

/// Result of a head-on collision of two particles.
struct Collision {
  double restitution = 0.0;  ///< -(relative normal velocity after) / (before)
  double duration = 0.0;     ///< s, contact start and end interpolated between steps
};

/// Runs two equal spheres (radius r) head-on at relative speed v until they separate.
inline Collision collide(SceneConfig scene, double r, double v, double dt) {
  scene.time.dt = dt;
  Particles p;
  const double gap = 0.02 * r;
  p.add(Vec3(-r - 0.5 * gap, 0.0, 0.5), r, scene.material.density);
  p.add(Vec3(r + 0.5 * gap, 0.0, 0.5), r, scene.material.density);
  p.velocity[0] = Vec3(0.5 * v, 0.0, 0.0);
  p.velocity[1] = Vec3(-0.5 * v, 0.0, 0.0);
  Simulation sim(scene, std::move(p));
  double prev = overlap(sim.particles(), 0, 1);
  double t_start = -1.0;
  Collision c;
  for (int k = 0; k < 10'000'000; ++k) {
    sim.step();
    const double ov = overlap(sim.particles(), 0, 1);
    const double t0 = sim.time() - sim.dt();  // time of `prev`
    if (t_start < 0.0 && ov > 0.0) t_start = t0 + sim.dt() * (-prev) / (ov - prev);
    if (t_start >= 0.0 && ov <= 0.0) {
      c.duration = t0 + sim.dt() * prev / (prev - ov) - t_start;
      const Particles& q = sim.particles();
      c.restitution = (q.velocity[1].x() - q.velocity[0].x()) / v;
      return c;
    }
    prev = ov;
  }
  return c;
}

}  // namespace drumlab::test
