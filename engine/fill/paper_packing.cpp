#include "engine/fill/paper_packing.hpp"

#include <cmath>

#include <fmt/format.h>

namespace drumlab {
namespace {

/// Lattice sites (2k + 1) r, k >= 0, whose sphere fits in [0, length]: (2k + 2) r <= length, with
/// a relative tolerance so that a sphere touching the face is kept despite rounding.
std::size_t sites_along(double length, double r) {
  return static_cast<std::size_t>(std::floor(length / (2.0 * r) * (1.0 + 1e-12)));
}

void check_inputs(const Vec3& box, const std::array<double, 3>& radii) {
  if (!box.allFinite() || !(box.minCoeff() > 0.0)) {
    throw InputError(fmt::format("paper packing: box sizes must be positive, got [{}, {}, {}]",
                                 box.x(), box.y(), box.z()));
  }
  for (double r : radii) {
    if (!(r > 0.0) || !std::isfinite(r)) {
      throw InputError(fmt::format("paper packing: radius must be positive, got {}", r));
    }
  }
}

}  // namespace

std::array<std::size_t, 3> paper_packing_counts(const Vec3& box,
                                                const std::array<double, 3>& radii) {
  check_inputs(box, radii);
  const double strip = box.y() / 3.0;
  std::array<std::size_t, 3> counts{};
  for (std::size_t c = 0; c < 3; ++c) {
    const double r = radii[c];
    counts[c] = sites_along(box.x(), r) * sites_along(strip, r) * sites_along(box.z(), r);
  }
  return counts;
}

Particles paper_packing(const Vec3& box, const std::array<double, 3>& radii, double density) {
  const auto counts = paper_packing_counts(box, radii);
  if (!(density > 0.0) || !std::isfinite(density)) {
    throw InputError(fmt::format("paper packing: density must be positive, got {}", density));
  }
  Particles p;
  p.reserve(counts[0] + counts[1] + counts[2]);
  const double strip = box.y() / 3.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double r = radii[c];
    const double y0 = static_cast<double>(c) * strip;
    const std::size_t nx = sites_along(box.x(), r);
    const std::size_t ny = sites_along(strip, r);
    const std::size_t nz = sites_along(box.z(), r);
    for (std::size_t j = 0; j < ny; ++j) {
      const double y = static_cast<double>(2 * j + 1) * r + y0;
      for (std::size_t k = 0; k < nz; ++k) {
        const double z = static_cast<double>(2 * k + 1) * r;
        for (std::size_t i = 0; i < nx; ++i) {
          const double x = static_cast<double>(2 * i + 1) * r;
          p.add(Vec3(x, y, z), r, density, static_cast<std::uint8_t>(c));
        }
      }
    }
  }
  return p;
}

Particles paper_packing(const Vec3& box, double density) {
  return paper_packing(box, kPaperRadii, density);
}

}  // namespace drumlab
