#pragma once
// What a restart checks of the particles it is handed (from a checkpoint, an MPI rank's share of
// one, or a state built in code), beyond the shapes of the arrays: the values a fill of the scene
// makes. A checkpoint of another scene, or one with a damaged dataset, is refused with one line
// naming the dataset and the row, before a step can turn it into an unstable run.
#include <optional>
#include <string_view>

#include "engine/particles.hpp"
#include "engine/scene/scene_validation.hpp"

namespace drumlab {

/// The first particle value that the scene's fill cannot have made, or nullopt: a size class the
/// scene lacks; a radius other than its class's; a mass, inverse mass or inverse inertia other
/// than the class's radius and the material's density give (relative 1e-12); a non-finite
/// position, velocity, angular velocity, force or torque; a non-finite value in a law part's
/// array (Particles::extra), or a liquid volume or bridge age below zero; an id used twice. The key
/// is the checkpoint's dataset and row ("particles/mass: row 12").
std::optional<SceneProblem> restart_particles_problem(const SceneConfig& scene, const Particles& p);

/// Throws InputError "<where>: particles: N in the checkpoint, the scene's fill.count is M (...)"
/// when a scene filled at random (which always places fill.count particles) is handed another
/// count; other fills are not checked here.
void check_restart_count(const SceneConfig& scene, std::size_t count, std::string_view where);

/// Throws InputError "<where>: <dataset>: row <i>: <reason>" for restart_particles_problem.
void check_restart_particles(const SceneConfig& scene, const Particles& p, std::string_view where);

}  // namespace drumlab
