#pragma once
// The paper's static packing (Lobovikov et al. 2021): three size classes, each a simple cubic
// lattice of touching spheres in its own strip of a box. Used for contact-search operation counts
// (`drumlab paper-table`), not as the start of a dynamic run.
#include <array>
#include <cstddef>

#include "engine/particles.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// Radii of the paper's small, medium and large spheres, m.
inline constexpr std::array<double, 3> kPaperRadii{0.005, 0.010, 0.015};

/// Spheres per class that paper_packing places in `box` (no particles are built).
std::array<std::size_t, 3> paper_packing_counts(const Vec3& box,
                                                const std::array<double, 3>& radii = kPaperRadii);

/// Box [0, box.x) x [0, box.y) x [0, box.z) split along y into three equal strips; strip c holds
/// spheres of radius radii[c] (size class c) on a simple cubic lattice with spacing 2 r, centres at
/// (2k + 1) r from the strip's lower faces; spheres that would stick out of the strip are left out.
/// Order: x fastest, then z, then y; strips small to large. For box [1.85, 1.80, 0.15]:
/// 166,500 + 19,320 + 6,100 spheres. Throws InputError for a non-positive box size, radius or
/// density.
Particles paper_packing(const Vec3& box, const std::array<double, 3>& radii, double density);

/// Same with the paper's radii 0.005, 0.010, 0.015 m.
Particles paper_packing(const Vec3& box, double density);

}  // namespace drumlab
