#pragma once
// A small turning drum with friction and rolling resistance on particles and walls, shared by the
// checkpoint/HDF5 and VTU tests: after settling it has persistent particle and wall contacts, so
// the tangential and wall history carry state from step to step.
#include <memory>
#include <string>

#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"

namespace drumlab::test {

inline std::string output_scene_text() {
  return R"(search = "m5"
[drum]
diameter = 0.2
depth = 0.05
omega = 3.0
[[particles]]
radius = 0.004
volume_fraction = 0.5
[[particles]]
radius = 0.008
volume_fraction = 0.5
[material]
density = 2500.0
youngs_modulus = 5e6
poisson_ratio = 0.3
restitution = 0.5
friction = 0.5
rolling_friction = 0.05
[wall]
youngs_modulus = 5e6
poisson_ratio = 0.3
restitution = 0.5
friction = 0.4
rolling_friction = 0.05
[fill]
count = 250
settle_time = 0.01
[time]
dt_factor = 0.2
duration = 0.01
[output]
diagnostics_every = 50
)";
}

inline SceneConfig output_scene() {
  return parse_scene(output_scene_text(), "output-test");
}

/// The scene filled and advanced `steps` steps (the drum turning throughout).
inline std::unique_ptr<Simulation> settled_simulation(const SceneConfig& scene,
                                                      std::uint64_t steps) {
  auto sim = std::make_unique<Simulation>(scene, random_fill(scene));
  sim->advance(steps);
  return sim;
}

}  // namespace drumlab::test
