#include "engine/stability.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include <fmt/format.h>

#include "engine/parallel/domain_hooks.hpp"

namespace drumlab {

namespace {

constexpr std::size_t kSiteValues = 11;

/// An overlap reached in fewer than about 10 steps of the bodies' relative motion (travel a step
/// above this share of the limit) is blamed on the time step; a slower one on the impact.
constexpr double kResolvedTravel = 0.1;

std::array<double, kSiteValues> pack(const OverlapSite& s) {
  return {static_cast<double>(s.id_a),
          static_cast<double>(s.id_b),
          static_cast<double>(s.wall),
          s.radius_a,
          s.radius_b,
          s.point.x(),
          s.point.y(),
          s.point.z(),
          s.relative_speed,
          s.closing_speed,
          static_cast<double>(s.mesh)};
}

OverlapSite unpack(const std::array<double, kSiteValues>& v) {
  OverlapSite s;
  s.id_a = static_cast<Index>(v[0]);
  s.id_b = static_cast<std::int64_t>(v[1]);
  s.wall = static_cast<WallPart>(static_cast<int>(v[2]));
  s.radius_a = v[3];
  s.radius_b = v[4];
  s.point = Vec3(v[5], v[6], v[7]);
  s.relative_speed = v[8];
  s.closing_speed = v[9];
  s.mesh = static_cast<std::int64_t>(v[10]);
  return s;
}

std::string_view wall_name(WallPart part) {
  switch (part) {
    case WallPart::cylinder:
      return "the drum mantle";
    case WallPart::cap_low:
      return "the end cap at z = 0";
    case WallPart::cap_high:
      return "the end cap at z = depth";
  }
  return "the wall";
}

std::string bodies(const OverlapSite& s) {
  if (s.is_wall() && s.mesh >= 0) {
    return fmt::format(
        "particle {} (radius {:.3g} mm) and triangle wall {} (counting [[wall.mesh]], then "
        "[[wall.lifters]], from 0)",
        s.id_a, 1e3 * s.radius_a, s.mesh);
  }
  if (s.is_wall()) {
    return fmt::format("particle {} (radius {:.3g} mm) and {}", s.id_a, 1e3 * s.radius_a,
                       wall_name(s.wall));
  }
  return fmt::format("particles {} and {} (radii {:.3g} and {:.3g} mm)", s.id_a, s.id_b,
                     1e3 * s.radius_a, 1e3 * s.radius_b);
}

}  // namespace

OverlapSite wall_site(const Particles& p, std::size_t i, WallPart part, const WallContact& c,
                      double omega) {
  OverlapSite s;
  s.id_a = p.id[i];
  s.wall = part;
  s.radius_a = p.radius[i];
  s.point = p.position[i] - (p.radius[i] - 0.5 * c.overlap) * c.normal;
  const Vec3 dv = p.velocity[i] - Drum::wall_velocity(s.point, omega);
  s.relative_speed = dv.norm();
  s.closing_speed = -dv.dot(c.normal);  // the normal points into the particle
  return s;
}

OverlapSite mesh_site(const Particles& p, std::size_t i, std::size_t mesh, const Vec3& normal,
                      double overlap, const Vec3& wall_velocity) {
  OverlapSite s;
  s.id_a = p.id[i];
  s.mesh = static_cast<std::int64_t>(mesh);
  s.radius_a = p.radius[i];
  s.point = p.position[i] - (p.radius[i] - 0.5 * overlap) * normal;
  const Vec3 dv = p.velocity[i] - wall_velocity;
  s.relative_speed = dv.norm();
  s.closing_speed = -dv.dot(normal);
  return s;
}

OverlapSite pair_site(const Particles& p, std::size_t i, std::size_t j, const Vec3& dx) {
  OverlapSite s;
  s.id_a = p.id[i];
  s.id_b = p.id[j];
  s.radius_a = p.radius[i];
  s.radius_b = p.radius[j];
  const double dist = dx.norm();
  const Vec3 n = dx / dist;  // from j to i
  const double delta = p.radius[i] + p.radius[j] - dist;
  s.point = p.position[i] - (p.radius[i] - 0.5 * delta) * n;
  const Vec3 dv = p.velocity[i] - p.velocity[j];
  s.relative_speed = dv.norm();
  s.closing_speed = -dv.dot(n);
  return s;
}

void reduce_overlap_site(DomainHooks& domain, double local_ratio, double global_ratio,
                         OverlapSite& site) {
  // Element-wise maxima: the rank that holds the largest ratio gives its values, the others
  // the lowest double.
  std::array<double, kSiteValues> v{};
  if (local_ratio == global_ratio) {
    v = pack(site);
  } else {
    v.fill(std::numeric_limits<double>::lowest());
  }
  domain.max(v);
  site = unpack(v);
}

std::string time_step_key(double dt, double rayleigh_time) {
  return fmt::format("time.dt (now {:.4g} s = {:.3g} Rayleigh times)", dt, dt / rayleigh_time);
}

std::string overlap_reason(const OverlapSite& site, double ratio, double max_overlap, double dt,
                           double rayleigh_time) {
  const double r_min = site.is_wall() ? site.radius_a : std::min(site.radius_a, site.radius_b);
  const double travel = site.relative_speed * dt / r_min;  // radii a step
  const std::string where = fmt::format(
      "overlap of {:.3g} radii (limit time.max_overlap = {:.3g}) between {} at ({:.3f}, {:.3f}, "
      "{:.3f}) m, meeting at {:.3g} m/s ({:.2g} m/s along the normal, {:.2g} radii a step)",
      ratio, max_overlap, bodies(site), site.point.x(), site.point.y(), site.point.z(),
      site.relative_speed, site.closing_speed, travel);
  if (travel > kResolvedTravel * max_overlap) {
    return fmt::format("{}; try a smaller {}", where, time_step_key(dt, rayleigh_time));
  }
  return fmt::format(
      "{}; the step resolves this impact, so a smaller {} hardly changes it: a stiffer "
      "material.youngs_modulus, a gentler flow (e.g. a lower cohesion.energy_density) or a larger "
      "time.max_overlap lets the run go on",
      where, time_step_key(dt, rayleigh_time));
}

UnstableError unstable_error(std::uint64_t step, double t, std::string_view why) {
  return UnstableError(fmt::format("unstable at step {} (t = {:.6g} s): {}", step, t, why));
}

}  // namespace drumlab
