#include "engine/spray/droplet_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "engine/periodic.hpp"

namespace drumlab {
namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// A uniform number in [0, 1) from 53 bits of a hash.
double unit(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

/// Two unit vectors normal to `d` (unit) and to each other.
std::pair<Vec3, Vec3> normal_basis(const Vec3& d) {
  const Vec3 helper = std::abs(d.x()) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
  const Vec3 e1 = d.cross(helper).normalized();
  return {e1, d.cross(e1)};
}

}  // namespace

DropletCloud::DropletCloud(std::vector<SprayConfig> sprays, const Drum& drum, const Vec3& gravity,
                           double patch)
    : sprays_(std::move(sprays)), drum_(drum), gravity_(gravity) {
  double smallest = std::numeric_limits<double>::infinity();
  for (SprayConfig& s : sprays_) {
    const double r = s.droplet_radius;
    const double v = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw InputError(
          fmt::format("spray '{}': droplet_radius {} gives no droplet volume", s.name, r));
    }
    if (!(s.direction.norm() > 0.0)) {
      throw InputError(fmt::format("spray '{}': direction must not be zero", s.name));
    }
    s.direction.normalize();
    volume_.push_back(v);
    if (s.at_wall == SprayAtWall::wet) smallest = std::min(smallest, v);
  }
  emitted_.assign(sprays_.size(), 0);
  absorbed_.assign(sprays_.size(), 0);
  lost_.assign(sprays_.size(), 0);
  walled_.assign(sprays_.size(), 0);
  // A patch's rest below a millionth of the smallest droplet goes with the particle's share.
  if (std::isfinite(smallest))
    wall_film_ = std::make_unique<WallFilm>(drum, patch, 1e-6 * smallest);
}

Vec3 DropletCloud::droplet_direction(std::size_t s, std::uint64_t k) const {
  const SprayConfig& c = sprays_[s];
  const std::uint64_t key = splitmix64(splitmix64(s + 1) ^ k);
  const double u1 = unit(key), u2 = unit(splitmix64(key));
  const double half = 0.5 * c.angle_deg * std::numbers::pi / 180.0;
  const Vec3& d = c.direction;
  if (c.shape == SprayShape::flat_fan) {
    Vec3 f = c.fan_axis - c.fan_axis.dot(d) * d;
    f = f.norm() > 1e-12 ? f.normalized() : normal_basis(d).first;
    const double theta = (2.0 * u1 - 1.0) * half;
    return std::cos(theta) * d + std::sin(theta) * f;
  }
  // Uniform over the cap's solid angle: cos(theta) uniform in [cos(half), 1].
  const double cos_t = 1.0 - u1 * (1.0 - std::cos(half));
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
  const double phi = 2.0 * std::numbers::pi * u2;
  const auto [e1, e2] = normal_basis(d);
  return cos_t * d + sin_t * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

std::uint64_t DropletCloud::emitted_by(std::size_t s, double t) const {
  const SprayConfig& c = sprays_[s];
  const double span = std::min(t, c.stop) - c.start;
  if (!(c.rate > 0.0) || !(span > 0.0)) return 0;
  // A droplet due within 1e-9 of a droplet's period counts: the count of a whole number of
  // periods does not depend on how the division rounds.
  return static_cast<std::uint64_t>(std::floor(span * c.rate / volume_[s] + 1e-9));
}

bool DropletCloud::active(double t) const {
  if (!droplets_.empty()) return true;
  for (std::size_t s = 0; s < sprays_.size(); ++s) {
    if (sprays_[s].rate > 0.0 && t < sprays_[s].stop &&
        emitted_by(s, sprays_[s].stop) > emitted_[s]) {
      return true;
    }
  }
  return false;
}

SprayTotals DropletCloud::totals() const {
  SprayTotals t;
  std::vector<std::uint64_t> airborne(sprays_.size(), 0);
  for (const Droplet& d : droplets_) ++airborne[d.spray];
  for (std::size_t s = 0; s < sprays_.size(); ++s) {
    const double v = volume_[s];
    t.sprayed += static_cast<double>(emitted_[s]) * v;
    t.airborne += static_cast<double>(airborne[s]) * v;
    t.absorbed += static_cast<double>(absorbed_[s]) * v;
    t.lost += static_cast<double>(lost_[s]) * v;
    t.walled += static_cast<double>(walled_[s]) * v;
    t.emitted_count += emitted_[s];
    t.absorbed_count += absorbed_[s];
    t.lost_count += lost_[s];
    t.walled_count += walled_[s];
  }
  if (wall_film_) t.on_wall = wall_film_->volume();
  t.taken_from_wall = t.walled - t.on_wall;
  return t;
}

void DropletCloud::bin_particles(std::span<const Vec3> position, double cell, const Vec3& low,
                                 const Vec3& high) {
  cell_ = cell;
  low_ = low;
  nx_ =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((high.x() - low.x()) / cell)));
  ny_ =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((high.y() - low.y()) / cell)));
  // z: the drum's whole depth in cells of at least `cell` that tile it (the period's too).
  nz_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(drum_.depth() / cell)));
  const std::size_t cells = static_cast<std::size_t>(nx_ * ny_ * nz_);
  cell_start_.assign(cells + 1, 0);
  cell_of_.assign(position.size(), -1);
  const double cz = drum_.depth() / static_cast<double>(nz_);
  for (std::size_t i = 0; i < position.size(); ++i) {
    const Vec3& x = position[i];
    if (x.x() < low.x() || x.x() > high.x() || x.y() < low.y() || x.y() > high.y()) continue;
    const auto ix = std::min(nx_ - 1, static_cast<std::int64_t>((x.x() - low.x()) / cell));
    const auto iy = std::min(ny_ - 1, static_cast<std::int64_t>((x.y() - low.y()) / cell));
    const auto iz =
        std::clamp(static_cast<std::int64_t>(std::floor(x.z() / cz)), std::int64_t{0}, nz_ - 1);
    cell_of_[i] = (iz * ny_ + iy) * nx_ + ix;
    ++cell_start_[static_cast<std::size_t>(cell_of_[i]) + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(cell_start_[cells]);
  cell_fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < position.size(); ++i) {
    if (cell_of_[i] >= 0)
      cell_items_[cell_fill_[static_cast<std::size_t>(cell_of_[i])]++] =
          static_cast<std::uint32_t>(i);
  }
}

std::int64_t DropletCloud::first_hit(const Vec3& a, const Vec3& b, double rd,
                                     std::span<const Vec3> position, std::span<const double> radius,
                                     std::span<const std::uint32_t> id) const {
  const double period = drum_.period();
  const double cz = drum_.depth() / static_cast<double>(nz_);
  const auto ix = static_cast<std::int64_t>(std::floor((a.x() - low_.x()) / cell_));
  const auto iy = static_cast<std::int64_t>(std::floor((a.y() - low_.y()) / cell_));
  const auto iz =
      std::clamp(static_cast<std::int64_t>(std::floor(a.z() / cz)), std::int64_t{0}, nz_ - 1);
  const Vec3 d = b - a;
  const double dd = d.squaredNorm();
  std::int64_t best = -1;
  double best_s = 2.0;
  // The z layers around the droplet: wrapped across periodic ends, each visited once.
  std::int64_t layers[3];
  int n_layers = 0;
  for (std::int64_t k = iz - 1; k <= iz + 1; ++k) {
    std::int64_t z = k;
    if (period > 0.0) {
      z = ((k % nz_) + nz_) % nz_;
    } else if (k < 0 || k >= nz_) {
      continue;
    }
    if (std::find(layers, layers + n_layers, z) == layers + n_layers) layers[n_layers++] = z;
  }
  for (int l = 0; l < n_layers; ++l) {
    for (std::int64_t y = std::max<std::int64_t>(0, iy - 1); y <= std::min(ny_ - 1, iy + 1); ++y) {
      for (std::int64_t x = std::max<std::int64_t>(0, ix - 1); x <= std::min(nx_ - 1, ix + 1);
           ++x) {
        const auto c = static_cast<std::size_t>((layers[l] * ny_ + y) * nx_ + x);
        for (std::uint32_t q = cell_start_[c]; q < cell_start_[c + 1]; ++q) {
          const std::uint32_t i = cell_items_[q];
          // The particle's image nearest the droplet's start.
          const Vec3 f =
              period > 0.0 ? Vec3(-nearest_image(position[i], a, period)) : Vec3(a - position[i]);
          const double reach = radius[i] + rd;
          const double c0 = f.squaredNorm() - reach * reach;
          double s = 0.0;
          if (c0 > 0.0) {
            if (dd == 0.0) continue;
            const double half_b = f.dot(d);
            const double disc = half_b * half_b - dd * c0;
            if (half_b >= 0.0 || disc < 0.0) continue;  // moving away, or passing by
            s = (-half_b - std::sqrt(disc)) / dd;
            if (s > 1.0) continue;
          }
          if (s < best_s || (s == best_s && id[i] < id[static_cast<std::size_t>(best)])) {
            best_s = s;
            best = i;
          }
        }
      }
    }
  }
  return best;
}

SprayStep DropletCloud::advance(double t, double dt, std::span<const Vec3> position,
                                std::span<const double> radius, std::span<const std::uint32_t> id,
                                std::span<double> film, double angle) {
  SprayStep step;
  const double t1 = t + dt;
  // Newborn droplets join at the nozzle with the time they fly in this step as their start.
  start_.clear();
  for (const Droplet& d : droplets_) start_.push_back(d.position);
  std::vector<double>& flight = flight_;
  flight.assign(droplets_.size(), dt);
  for (std::size_t s = 0; s < sprays_.size(); ++s) {
    const SprayConfig& c = sprays_[s];
    const std::uint64_t target = emitted_by(s, t1);
    for (std::uint64_t k = emitted_[s] + 1; k <= target; ++k) {
      const double born = c.start + static_cast<double>(k) * volume_[s] / c.rate;
      droplets_.push_back({c.position, c.droplet_speed * droplet_direction(s, k), k,
                           static_cast<std::uint32_t>(s)});
      start_.push_back(c.position);
      flight.push_back(std::clamp(t1 - born, 0.0, dt));
      ++step.emitted;
    }
    emitted_[s] = std::max(emitted_[s], target);
  }
  fly(position, radius, id, film, angle, step);
  if (wall_film_) step.taken_from_wall = wall_film_->wipe(angle, position, radius, id, film);
  return step;
}

void DropletCloud::fly(std::span<const Vec3> position, std::span<const double> radius,
                       std::span<const std::uint32_t> id, std::span<double> film, double angle,
                       SprayStep& step) {
  std::vector<double>& flight = flight_;
  if (droplets_.empty()) return;
  // Fly: exact for constant gravity.
  double longest = 0.0, rd_max = 0.0;
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high = -low;
  for (std::size_t q = 0; q < droplets_.size(); ++q) {
    Droplet& d = droplets_[q];
    const double tau = flight[q];
    d.position = start_[q] + tau * d.velocity + 0.5 * tau * tau * gravity_;
    d.velocity += tau * gravity_;
    longest = std::max(longest, (d.position - start_[q]).norm());
    rd_max = std::max(rd_max, sprays_[d.spray].droplet_radius);
    low = low.cwiseMin(start_[q]).cwiseMin(d.position);
    high = high.cwiseMax(start_[q]).cwiseMax(d.position);
  }
  double r_max = 0.0;
  for (const double r : radius) r_max = std::max(r_max, r);
  // Cells no smaller than a particle's reach plus the longest path (so the 27 cells around a
  // droplet's start hold every particle its path can touch), and no more cells than about one
  // per particle in the drum's volume.
  const double box = 4.0 * drum_.radius() * drum_.radius() * drum_.depth();
  const double sparse =
      std::cbrt(box / static_cast<double>(std::max<std::size_t>(position.size(), 1024)));
  const double cell = std::max(r_max + rd_max + longest, sparse);
  if (!position.empty()) {
    bin_particles(position, cell, low - Vec3::Constant(cell), high + Vec3::Constant(cell));
  }
  kept_.clear();
  for (std::size_t q = 0; q < droplets_.size(); ++q) {
    Droplet d = droplets_[q];
    const double rd = sprays_[d.spray].droplet_radius;
    const std::int64_t hit =
        position.empty() ? -1 : first_hit(start_[q], d.position, rd, position, radius, id);
    if (hit >= 0) {
      film[static_cast<std::size_t>(hit)] += volume_[d.spray];
      ++absorbed_[d.spray];
      ++step.absorbed;
      continue;
    }
    if (drum_.gap(d.position, rd) <= 0.0) {
      if (sprays_[d.spray].at_wall == SprayAtWall::wet) {
        wall_film_->deposit(d.position, angle, volume_[d.spray]);
        ++walled_[d.spray];
        ++step.walled;
      } else {
        ++lost_[d.spray];
        ++step.lost;
      }
      continue;
    }
    if (drum_.periodic()) d.position.z() = drum_.wrap_z(d.position.z());
    kept_.push_back(d);
  }
  droplets_.swap(kept_);
}

void DropletCloud::restore(std::vector<Droplet> droplets, std::vector<std::uint64_t> emitted,
                           std::vector<std::uint64_t> absorbed, std::vector<std::uint64_t> lost,
                           std::vector<std::uint64_t> walled, std::vector<double> wall_film) {
  const std::size_t n = sprays_.size();
  if (walled.empty()) walled.assign(n, 0);
  if (emitted.size() != n || absorbed.size() != n || lost.size() != n || walled.size() != n) {
    throw InputError(
        fmt::format("spray state: counts for {} nozzles, the scene has {}", emitted.size(), n));
  }
  std::vector<std::uint64_t> airborne(n, 0);
  for (const Droplet& d : droplets) {
    if (d.spray >= n) {
      throw InputError(
          fmt::format("spray state: a droplet of nozzle {}, the scene has {}", d.spray, n));
    }
    if (!d.position.allFinite() || !d.velocity.allFinite() || d.serial == 0 ||
        d.serial > emitted[d.spray]) {
      throw InputError(fmt::format(
          "spray state: droplet {} of nozzle {} is not a droplet the nozzle emitted in flight",
          d.serial, d.spray));
    }
    ++airborne[d.spray];
  }
  for (std::size_t s = 0; s < n; ++s) {
    if (absorbed[s] + lost[s] + walled[s] + airborne[s] != emitted[s]) {
      throw InputError(fmt::format(
          "spray state: nozzle {} emitted {} droplets but {} absorbed + {} lost + {} on the wall "
          "+ {} airborne",
          s, emitted[s], absorbed[s], lost[s], walled[s], airborne[s]));
    }
    if (walled[s] > 0 && sprays_[s].at_wall != SprayAtWall::wet) {
      throw InputError(
          fmt::format("spray state: nozzle {} put droplets on a wall it does not wet", s));
    }
  }
  if (wall_film_) {
    if (!wall_film.empty()) wall_film_->restore(std::move(wall_film));
  } else if (!wall_film.empty()) {
    throw InputError("spray state: a wall film for a scene whose nozzles do not wet the wall");
  }
  droplets_ = std::move(droplets);
  emitted_ = std::move(emitted);
  absorbed_ = std::move(absorbed);
  lost_ = std::move(lost);
  walled_ = std::move(walled);
}

SprayState DropletCloud::state() const {
  SprayState s{droplets_, emitted_, absorbed_, lost_, walled_, {}};
  if (wall_film_) s.wall_film.assign(wall_film_->patches().begin(), wall_film_->patches().end());
  return s;
}

void DropletCloud::restore(SprayState s) {
  restore(std::move(s.droplets), std::move(s.emitted), std::move(s.absorbed), std::move(s.lost),
          std::move(s.walled), std::move(s.wall_film));
}

}  // namespace drumlab
