#pragma once
// Every range of a scene, checked on its values in one place, whatever door they came in by: the
// TOML loader (which adds the file and line), the GUI's --edit and scene panel, save_scene, the
// contact model, a restart and the Python module. Parsing (types, unknown keys, keys that exclude
// each other) stays with the loader; what a value may be is decided here.
#include <optional>
#include <string>
#include <string_view>

#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// One unusable value: its dotted key as written in a scene file ("drum.diameter",
/// "particles[1].radius", "liquid.max_bridge_volume") and why ("must be > 0, got -1").
struct SceneProblem {
  std::string key;
  std::string reason;
};

/// The largest search margin a law may ask for, in smallest radii: a range beyond one
/// smallest-particle diameter is no neighbour interaction (a pendular bridge ruptures well within
/// it) and would list (1 + margin / (2 r))^3 times the pairs of a dry search.
inline constexpr double kMaxRangeRadii = 2.0;

/// The first problem of the whole scene, in the order of a scene file's tables, or nullopt.
std::optional<SceneProblem> scene_problem(const SceneConfig& scene);

/// The first problem of what a contact model reads (materials, [contact], [liquid], [cohesion],
/// each range against the smallest class radius when the scene has classes), or nullopt.
std::optional<SceneProblem> law_problem(const SceneConfig& scene);

/// Throws InputError "<where>: <key>: <reason>" for scene_problem(scene); `where` defaults to
/// the scene's source file (or its name when it has none).
void validate(const SceneConfig& scene, std::string_view where = {});

/// Same for law_problem(scene).
void validate_laws(const SceneConfig& scene, std::string_view where = {});

}  // namespace drumlab
