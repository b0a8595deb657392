#pragma once
// The minimum image along a periodic z (periodic drum ends): the one formula every distance,
// overlap, contact line and coordination count across the periodic boundary uses.
#include "engine/types.hpp"

namespace drumlab {

/// The z component of a separation reduced to its nearest image, for a period > 0 and dz the
/// difference of two coordinates in [0, period) (so one shift suffices); with period <= 0 (no
/// periodic ends) dz unchanged. Exactly half a period is left as it is.
[[gnu::always_inline]] inline double nearest_image_z(double dz, double period) {
  if (period > 0.0) {
    if (dz > 0.5 * period) {
      dz -= period;
    } else if (dz < -0.5 * period) {
      dz += period;
    }
  }
  return dz;
}

/// a - b with its z component reduced to the nearest image (see nearest_image_z).
[[gnu::always_inline]] inline Vec3 nearest_image(const Vec3& a, const Vec3& b, double period) {
  Vec3 d = a - b;
  d.z() = nearest_image_z(d.z(), period);
  return d;
}

}  // namespace drumlab
