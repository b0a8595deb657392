#include "engine/scene/material_check.hpp"

#include <cmath>

#include <fmt/format.h>

namespace drumlab {

std::optional<std::string> material_value_problem(std::string_view key, double value) {
  if (!std::isfinite(value)) return fmt::format("must be a finite number, got {}", value);
  if (key == "density" || key == "youngs_modulus") {
    if (!(value > 0.0)) return fmt::format("must be > 0, got {}", value);
  } else if (key == "poisson_ratio") {
    if (!(value > -1.0 && value < 0.5)) return fmt::format("must be in (-1, 0.5), got {}", value);
  } else if (key == "restitution") {
    if (!(value > 0.0 && value <= 1.0)) return fmt::format("must be in (0, 1], got {}", value);
  } else if (key == "friction" || key == "rolling_friction") {
    if (!(value >= 0.0)) return fmt::format("must be >= 0, got {}", value);
  }
  return std::nullopt;
}

std::optional<MaterialProblem> material_problem(const Material& m) {
  const std::pair<std::string_view, double> values[] = {{"youngs_modulus", m.youngs_modulus},
                                                        {"poisson_ratio", m.poisson_ratio},
                                                        {"restitution", m.restitution},
                                                        {"friction", m.friction},
                                                        {"rolling_friction", m.rolling_friction}};
  for (const auto& [key, value] : values) {
    if (auto reason = material_value_problem(key, value)) {
      return MaterialProblem{std::string(key), std::move(*reason)};
    }
  }
  return std::nullopt;
}

}  // namespace drumlab
