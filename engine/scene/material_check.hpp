#pragma once
// The ranges of a material's values, in one place: the scene loader reports a failing key with
// its file and table, the contact model refuses a material built in code.
#include <optional>
#include <string>
#include <string_view>

#include "engine/scene/scene_config.hpp"

namespace drumlab {

/// A material value out of range: its key ("youngs_modulus", ...) and why, e.g. "must be > 0, got
/// -1".
struct MaterialProblem {
  std::string key;
  std::string reason;
};

/// Why `value` is unusable for the material key `key` (density, youngs_modulus, poisson_ratio,
/// restitution, friction, rolling_friction), or nullopt if it is fine (or the key is not one).
std::optional<std::string> material_value_problem(std::string_view key, double value);

/// The first unusable contact value of `m` (youngs_modulus, poisson_ratio, restitution, friction,
/// rolling_friction; density is not used by contacts), or nullopt.
std::optional<MaterialProblem> material_problem(const Material& m);

}  // namespace drumlab
