#include "engine/drum.hpp"

#include <fmt/format.h>

namespace drumlab {

Drum::Drum(const DrumConfig& config)
    : radius_(0.5 * config.diameter),
      depth_(config.depth),
      periodic_(config.ends == DrumEnds::periodic) {
  if (!(config.diameter > 0.0) || !std::isfinite(config.diameter)) {
    throw InputError(fmt::format("drum.diameter must be positive, got {}", config.diameter));
  }
  if (!(config.depth > 0.0) || !std::isfinite(config.depth)) {
    throw InputError(fmt::format("drum.depth must be positive, got {}", config.depth));
  }
}

Vec3 drum_frame_gravity(const Vec3& lab_gravity, double tilt) {
  const double c = std::cos(tilt);
  const double s = std::sin(tilt);
  // R_x(tilt) maps drum to lab: z_hat -> (0, -sin t, cos t). Its transpose maps lab to drum.
  return Vec3(lab_gravity.x(), c * lab_gravity.y() + s * lab_gravity.z(),
              -s * lab_gravity.y() + c * lab_gravity.z());
}

}  // namespace drumlab
