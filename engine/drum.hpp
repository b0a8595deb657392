#pragma once
// The analytic rotating drum, in its own frame: a cylinder of radius R = D/2 about the z axis,
// with ends at z = 0 and z = H that are either end caps (rotating with the drum) or periodic.
// The wall surface moves with velocity omega z_hat x r at the point r.
#include <algorithm>
#include <array>
#include <cmath>

#include "engine/scene/scene_config.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// The wall parts a particle can touch; index into per-particle wall history.
enum class WallPart : std::uint8_t { cylinder = 0, cap_low = 1, cap_high = 2 };
inline constexpr std::size_t kWallParts = 3;

/// A sphere against one wall part. overlap <= 0 means no contact; then normal is unspecified.
struct WallContact {
  Vec3 normal = Vec3::Zero();  ///< unit normal from the wall into the particle
  double overlap = 0.0;        ///< m
};

class Drum {
 public:
  /// Throws InputError for a non-positive diameter or depth.
  explicit Drum(const DrumConfig& config);

  double radius() const { return radius_; }
  double depth() const { return depth_; }
  bool periodic() const { return periodic_; }
  /// The period of z for the minimum image (nearest_image_z): the depth with periodic ends, else 0.
  double period() const { return periodic_ ? depth_ : 0.0; }

  /// Contact of a sphere (centre x, radius r) with the cylinder: overlap = rho + r - R.
  WallContact cylinder_contact(const Vec3& x, double r) const {
    const double rho2 = x.x() * x.x() + x.y() * x.y();
    const double reach = radius_ - r;  // rho beyond which the sphere touches
    if (reach > 0.0 && rho2 <= reach * reach) return {};
    const double rho = std::sqrt(rho2);
    if (rho == 0.0) return {};  // on the axis of a drum thinner than the particle: no direction
    return {Vec3(-x.x() / rho, -x.y() / rho, 0.0), rho + r - radius_};
  }

  /// Contact with the end cap at z = 0 (cap_low) or z = H (cap_high). No contact when periodic.
  WallContact cap_contact(WallPart cap, const Vec3& x, double r) const {
    if (periodic_) return {};
    if (cap == WallPart::cap_low) return {Vec3(0.0, 0.0, 1.0), r - x.z()};
    return {Vec3(0.0, 0.0, -1.0), x.z() + r - depth_};
  }

  WallContact contact(WallPart part, const Vec3& x, double r) const {
    return part == WallPart::cylinder ? cylinder_contact(x, r) : cap_contact(part, x, r);
  }

  /// Gap (m) between a sphere and one wall part (a cap as if the ends were closed); negative
  /// when they overlap.
  double part_gap(WallPart part, const Vec3& x, double r) const {
    if (part == WallPart::cap_low) return x.z() - r;
    if (part == WallPart::cap_high) return depth_ - x.z() - r;
    return radius_ - std::sqrt(x.x() * x.x() + x.y() * x.y()) - r;
  }
  /// Smallest gap (m) between a sphere and the wall parts: the cylinder and, unless periodic,
  /// both caps; negative when it overlaps one of them.
  double gap(const Vec3& x, double r) const {
    const double g = part_gap(WallPart::cylinder, x, r);
    if (periodic_) return g;
    return std::min({g, part_gap(WallPart::cap_low, x, r), part_gap(WallPart::cap_high, x, r)});
  }

  /// Velocity of the wall surface (cylinder or caps) at point p (m/s): omega z_hat x p.
  static Vec3 wall_velocity(const Vec3& p, double omega) {
    return Vec3(-omega * p.y(), omega * p.x(), 0.0);
  }

  /// True if the centre lies inside the drum (radially within R + tol, and between the caps
  /// within tol unless periodic).
  bool contains_centre(const Vec3& x, double tol) const {
    const double rmax = radius_ + tol;
    if (x.x() * x.x() + x.y() * x.y() > rmax * rmax) return false;
    return periodic_ || (x.z() >= -tol && x.z() <= depth_ + tol);
  }

  /// Wraps z into [0, H) (periodic ends).
  double wrap_z(double z) const {
    if (z >= 0.0 && z < depth_) return z;
    double w = z - depth_ * std::floor(z / depth_);
    if (w >= depth_ || w < 0.0) w = 0.0;  // round-off at the period boundary
    return w;
  }

 private:
  double radius_ = 0.0;
  double depth_ = 0.0;
  bool periodic_ = false;
};

/// Lab-frame gravity expressed in the drum frame of a drum whose axis is tilted by `tilt` (rad)
/// from horizontal, descending towards +z: the drum frame is the lab frame rotated by `tilt`
/// about x, so g_drum = R_x(tilt)^T g_lab. For g_lab = (0, -g, 0): (0, -g cos t, g sin t).
Vec3 drum_frame_gravity(const Vec3& lab_gravity, double tilt);

}  // namespace drumlab
