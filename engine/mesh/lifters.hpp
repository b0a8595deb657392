#pragma once
// Generated lifters (flights) as triangle meshes, without a file (issue "Drums as they are
// built": [[wall.lifters]]): `count` blades spaced evenly round the mantle of a drum of radius R,
// each a closed box standing `height` in from the mantle (and `thickness` into it, so no gap
// opens at the wall), `length` along the axis (centred on the drum's depth); `angled` lifters
// carry a tip at the blade's inner end, bent by `angle` from the inward radial towards the
// direction the drum turns (90 degrees: an L), so that they cup the material they lift. In the
// drum's own frame (turning with it), lifter k at angle phase + 2 pi k / count.
#include <vector>

#include "engine/mesh/triangle_mesh.hpp"

namespace drumlab {

enum class LifterShape { straight, angled };

struct LifterSpec {
  int count = 4;
  double height = 0.0;     ///< radial, m (> 0, < R)
  double length = 0.0;     ///< axial, m; 0: the drum's depth
  double thickness = 0.0;  ///< m; 0: height / 8
  LifterShape shape = LifterShape::straight;
  double angle = 1.5707963267948966;  ///< angled: the tip's bend from the inward radial, rad
  double tip = 0.0;                   ///< angled: the tip's length, m; 0: height / 2
  double phase = 0.0;                 ///< the first lifter's angle, rad
  int turn_sign = 1;                  ///< +1: the drum turns counter-clockwise (omega > 0)
};

/// The corners of a closed box (12 triangles, outward normals) with centre `c`, unit axes
/// `a`, `b`, `a x b` and half extents `h`.
std::vector<std::array<Vec3, 3>> box_triangles(const Vec3& c, const Vec3& a, const Vec3& b,
                                               const Vec3& h);

/// The lifters' triangles in the drum's frame. Throws InputError (naming "wall.lifters") for a
/// count below 1, a height not in (0, R), a length above the depth, an angle outside (0, pi).
std::vector<std::array<Vec3, 3>> lifter_triangles(const LifterSpec& spec, double drum_radius,
                                                  double drum_depth);

}  // namespace drumlab
