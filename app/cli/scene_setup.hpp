#pragma once
// Shared by the run/demo/info commands and the benches: what they derive from a scene.
#include <string>
#include <string_view>

#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab::cli {

/// Froude number omega^2 R / g (g = |gravity| in the drum's cross-section plane).
double froude_number(const SceneConfig& scene);
/// Flow regime predicted from the Froude number (Mellmann 2001 ranges).
std::string regime_for_froude(double fr);

/// Path of a scene shipped in scenes/.
std::string shipped_scene(std::string_view file_name);

}  // namespace drumlab::cli
