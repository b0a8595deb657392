#pragma once
// A 3-vector of plain doubles with the few Eigen-style operations the contact laws use
// (engine/contact/hertz_mindlin.hpp, rolling_resistance.hpp are written for either). GCC 12
// vectorizes the contact kernel's loop over contacts (engine/contact/contact_kernel.hpp) only when
// every vector in it is a plain aggregate: it does not look through Eigen::Vector3d's storage
// ("no vectype for stmt" in -fopt-info-vec).
#include <cmath>

#include "engine/types.hpp"

namespace drumlab {

struct LaneVec {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  static LaneVec Zero() { return {}; }

  double dot(const LaneVec& o) const { return x * o.x + y * o.y + z * o.z; }
  double squaredNorm() const { return dot(*this); }
  double norm() const { return std::sqrt(squaredNorm()); }
  LaneVec cross(const LaneVec& o) const {
    return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x};
  }
  LaneVec operator-() const { return {-x, -y, -z}; }
  LaneVec operator+(const LaneVec& o) const { return {x + o.x, y + o.y, z + o.z}; }
  LaneVec operator-(const LaneVec& o) const { return {x - o.x, y - o.y, z - o.z}; }
  LaneVec operator*(double s) const { return {x * s, y * s, z * s}; }
  LaneVec operator/(double s) const { return {x / s, y / s, z / s}; }
  LaneVec& operator+=(const LaneVec& o) { return *this = *this + o; }
  LaneVec& operator-=(const LaneVec& o) { return *this = *this - o; }
  LaneVec& operator*=(double s) { return *this = *this * s; }
};

inline LaneVec operator*(double s, const LaneVec& v) {
  return {s * v.x, s * v.y, s * v.z};
}

/// c ? a : b, component by component, without a branch.
inline LaneVec select(bool c, const LaneVec& a, const LaneVec& b) {
  return {c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z};
}
inline Vec3 select(bool c, const Vec3& a, const Vec3& b) {
  return {c ? a.x() : b.x(), c ? a.y() : b.y(), c ? a.z() : b.z()};
}

}  // namespace drumlab
