#pragma once
// Shared by the run/demo/info commands: load a scene and derive what they report.
#include <string>
#include <string_view>

#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab::cli {

/// Loads a dynamic scene (random or file fill). A static paper packing is refused with a clear
/// error.
SceneConfig load_dynamic_scene(const std::string& file);

/// Froude number omega^2 R / g (g = |gravity| in the drum's cross-section plane).
double froude_number(const SceneConfig& scene);
/// Flow regime predicted from the Froude number (Mellmann 2001 ranges).
std::string regime_for_froude(double fr);

/// Path of a scene shipped in scenes/.
std::string shipped_scene(std::string_view file_name);

}  // namespace drumlab::cli
