#pragma once
// Random loose fill of the lower part of the drum, without overlaps (random sequential addition).
#include <cstddef>
#include <vector>

#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// Particles per size class: scene.fill.count split in proportion to volume_fraction / r^3 (so
/// every class gets its share of the solid volume), largest-remainder rounding so the counts sum
/// exactly to fill.count. 18825 particles of radii 5, 10, 15 mm in equal volume: 16200, 2025, 600.
std::vector<std::size_t> class_counts(const SceneConfig& scene);

/// Places class_counts(scene) particles at rest, largest first, at uniformly random non-overlapping
/// positions inside the drum (centres at least one radius from the mantle and from z = 0, depth),
/// in the part of the drum below a level chosen so that the solid fraction of that region is
/// fill.volume_fraction. "Below" follows the in-plane component of scene.gravity (-y if none).
/// When a particle finds no free spot after many tries the level is raised; if the whole drum is
/// full, throws InputError. Deterministic for fill.seed (std::mt19937_64). size_class is the class
/// index, density the particle material's. Needs fill.kind == random.
Particles random_fill(const SceneConfig& scene);

}  // namespace drumlab
