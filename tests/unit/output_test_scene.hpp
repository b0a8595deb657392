#pragma once
// A small turning drum with friction and rolling resistance on particles and walls, shared by the
// checkpoint/HDF5 and VTU tests: after settling it has persistent particle and wall contacts, so
// the tangential and wall history carry state from step to step.
#include <memory>
#include <string>

#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"
#include "tests/small_drum_text.hpp"

namespace drumlab::test {

inline std::string output_scene_text() {
  SmallDrumText t;
  t.omega = "3.0";
  t.rolling_friction = "0.05";
  t.wall =
      "youngs_modulus = 5e6\npoisson_ratio = 0.3\nrestitution = 0.5\nfriction = 0.4\n"
      "rolling_friction = 0.05";
  t.fill = "count = 250\nsettle_time = 0.01";
  t.output = "diagnostics_every = 50";
  return t.text();
}

/// The same drum wet: pendular bridges ([liquid]) of 1e-9 m^3 (rupture gap 1 mm), so bonds form.
inline std::string wet_output_scene_text() {
  return output_scene_text() +
         "[liquid]\nsurface_tension = 0.072\ncontact_angle_deg = 0\nbridge_volume = 1e-9\n";
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
