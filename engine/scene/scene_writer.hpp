#pragma once
// Writes a SceneConfig as a scene file that load_scene reads back to the same SceneConfig (every
// field but `source`, doubles exactly): the inverse of engine/scene/scene_loader.cpp, with the keys
// of scenes/README.md. Keys the scene's choices leave unused are not written and load back as
// their defaults: the fill keys of the other fill kinds, `dt_factor` when `dt` is set,
// `linear_stiffness` with the Hertz law, the [liquid] values of a dry scene and the wall's density
// (the wall has none). Optional keys equal to their default are written anyway, except [wall] keys
// equal to the [material] value (they follow the material, as in a hand-written scene) and an
// `[output] directory` equal to the default `out/<name>`.
#include <filesystem>
#include <string>

#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// The scene as TOML text. `fill.file` is written relative to `folder` (the folder the text will
/// be saved in) when it can be, else as an absolute path.
std::string scene_to_toml(const SceneConfig& scene, const std::filesystem::path& folder);
/// Same, relative to the folder of `scene.source` (where parse_scene(text, scene.source) resolves
/// it).
std::string scene_to_toml(const SceneConfig& scene);

/// toml++'s output (`out << table`) with every float reprinted as the shortest decimal that
/// parses back to the same bits (Debian's toml++ prints 17 digits: 0.59999999999999998).
std::string with_shortest_floats(const std::string& toml_text);

/// Writes scene_to_toml(scene, folder of `file`) to `file` atomically (engine/io/atomic_file.hpp):
/// a failed write leaves no file. Throws InputError with one line naming the file.
void save_scene(const SceneConfig& scene, const std::filesystem::path& file);

}  // namespace drumlab
