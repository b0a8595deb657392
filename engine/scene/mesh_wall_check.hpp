#pragma once
// The values of [[wall.mesh]] and [[wall.lifters]] (scene_validation.hpp's rules for the triangle
// walls); the files themselves are read and checked by engine/mesh/wall_meshes.hpp.
#include <optional>

#include "engine/scene/scene_validation.hpp"

namespace drumlab {

/// The first unusable value of the scene's triangle walls, or nullopt.
std::optional<SceneProblem> mesh_wall_problem(const SceneConfig& scene);

}  // namespace drumlab
