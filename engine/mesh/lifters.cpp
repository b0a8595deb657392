#include "engine/mesh/lifters.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Geometry>

namespace drumlab {

std::vector<std::array<Vec3, 3>> box_triangles(const Vec3& c, const Vec3& a, const Vec3& b,
                                               const Vec3& h) {
  // The eight corners once (so that the faces share them bit for bit), corner(i) at
  // c + s0 h0 a + s1 h1 b + s2 h2 (a x b), s_k = -1 or +1 by bit k of i.
  const Vec3 e[3] = {a, b, a.cross(b)};
  std::array<Vec3, 8> corner;
  for (int i = 0; i < 8; ++i) {
    Vec3 x = c;
    for (int k = 0; k < 3; ++k) x += ((i >> k) & 1 ? 1.0 : -1.0) * h[k] * e[k];
    corner[static_cast<std::size_t>(i)] = x;
  }
  // Each face by its four corners, counter-clockwise seen from outside.
  static constexpr int kFaces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5},   // -a, +a
                                       {0, 1, 5, 4}, {2, 6, 7, 3},   // -b, +b
                                       {0, 2, 3, 1}, {4, 5, 7, 6}};  // -(a x b), +(a x b)
  std::vector<std::array<Vec3, 3>> out;
  for (const auto& f : kFaces) {
    out.push_back({corner[f[0]], corner[f[1]], corner[f[2]]});
    out.push_back({corner[f[0]], corner[f[2]], corner[f[3]]});
  }
  return out;
}

std::vector<std::array<Vec3, 3>> lifter_triangles(const LifterSpec& s, double radius,
                                                  double depth) {
  const auto fail = [](const std::string& key, const std::string& why) {
    return InputError(fmt::format("wall.lifters.{}: {}", key, why));
  };
  if (s.count < 1) throw fail("count", "must be at least 1");
  if (!(s.height > 0.0 && s.height < radius)) {
    throw fail("height", fmt::format("must lie in (0, R = {:g} m)", radius));
  }
  const double length = s.length > 0.0 ? s.length : depth;
  if (!(length <= depth)) throw fail("length", fmt::format("exceeds the depth {:g} m", depth));
  const double thick = s.thickness > 0.0 ? s.thickness : s.height / 8.0;
  if (!(thick < s.height)) throw fail("thickness", "must be below the height");
  if (s.shape == LifterShape::angled && !(s.angle > 0.0 && s.angle < std::numbers::pi)) {
    throw fail("angle_deg", "must lie in (0, 180) degrees");
  }
  const double tip = s.tip > 0.0 ? s.tip : 0.5 * s.height;
  std::vector<std::array<Vec3, 3>> out;
  const Vec3 z = Vec3::UnitZ();
  for (int k = 0; k < s.count; ++k) {
    const double phi = s.phase + 2.0 * std::numbers::pi * k / s.count;
    const Vec3 er(std::cos(phi), std::sin(phi), 0.0);
    const Vec3 et = static_cast<double>(s.turn_sign) * z.cross(er);  // the way the wall moves
    // The blade: from R - height in to R + thickness out (into the wall), centred on its angle.
    const double r_in = radius - s.height, r_out = radius + thick;
    const Vec3 centre = 0.5 * (r_in + r_out) * er + 0.5 * depth * z;
    for (const auto& t :
         box_triangles(centre, er, z, Vec3(0.5 * (r_out - r_in), 0.5 * length, 0.5 * thick))) {
      out.push_back(t);
    }
    if (s.shape == LifterShape::angled) {  // the tip from the blade's inner end
      const Vec3 d = std::cos(s.angle) * (-er) + std::sin(s.angle) * et;
      const Vec3 start = (r_in + 0.5 * thick) * er + 0.5 * depth * z;
      for (const auto& t :
           box_triangles(start + 0.5 * tip * d, d, z, Vec3(0.5 * tip, 0.5 * length, 0.5 * thick))) {
        out.push_back(t);
      }
    }
  }
  return out;
}

}  // namespace drumlab
