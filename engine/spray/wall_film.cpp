#include "engine/spray/wall_film.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace drumlab {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::int64_t cells(double length, double side) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(length / side)));
}

}  // namespace

WallFilm::WallFilm(const Drum& drum, double side, double residue) : drum_(drum), residue_(residue) {
  if (!(side > 0.0) || !std::isfinite(side)) {
    throw InputError(fmt::format("wall film: patch side {} m must be positive", side));
  }
  n_theta_ = cells(kTwoPi * drum.radius(), side);
  n_z_ = cells(drum.depth(), side);
  n_ring_ = drum.periodic() ? 0 : cells(drum.radius(), side);
  volume_.assign(static_cast<std::size_t>(n_theta_ * (n_z_ + 2 * n_ring_)), 0.0);
}

std::size_t WallFilm::patch(WallPart part, const Vec3& x, double angle) const {
  double theta = std::atan2(x.y(), x.x()) - angle;
  theta -= kTwoPi * std::floor(theta / kTwoPi);
  const auto sector =
      std::clamp(static_cast<std::int64_t>(theta / kTwoPi * static_cast<double>(n_theta_)),
                 std::int64_t{0}, n_theta_ - 1);
  if (part == WallPart::cylinder) {
    const double z = drum_.periodic() ? drum_.wrap_z(x.z()) : x.z();
    const auto layer =
        std::clamp(static_cast<std::int64_t>(z / drum_.depth() * static_cast<double>(n_z_)),
                   std::int64_t{0}, n_z_ - 1);
    return static_cast<std::size_t>(layer * n_theta_ + sector);
  }
  const double rho = std::hypot(x.x(), x.y());
  const auto ring =
      std::clamp(static_cast<std::int64_t>(rho / drum_.radius() * static_cast<double>(n_ring_)),
                 std::int64_t{0}, n_ring_ - 1);
  const std::int64_t cap = part == WallPart::cap_low ? 0 : 1;
  return static_cast<std::size_t>((n_z_ + cap * n_ring_ + ring) * n_theta_ + sector);
}

double WallFilm::area(std::size_t k) const {
  const auto row = static_cast<std::int64_t>(k) / n_theta_;
  const double sectors = static_cast<double>(n_theta_);
  if (row < n_z_) {
    return kTwoPi * drum_.radius() * drum_.depth() / (sectors * static_cast<double>(n_z_));
  }
  const auto ring = (row - n_z_) % n_ring_;
  const double width = drum_.radius() / static_cast<double>(n_ring_);
  const double r0 = width * static_cast<double>(ring), r1 = r0 + width;
  return std::numbers::pi * (r1 * r1 - r0 * r0) / sectors;
}

void WallFilm::deposit(const Vec3& x, double angle, double v) {
  // The wall part the droplet is nearest to (the one it reached).
  WallPart part = WallPart::cylinder;
  if (!drum_.periodic()) {
    const double mantle = drum_.radius() - std::hypot(x.x(), x.y());
    const double low = x.z(), high = drum_.depth() - x.z();
    if (low < mantle && low <= high) part = WallPart::cap_low;
    if (high < mantle && high < low) part = WallPart::cap_high;
  }
  double& w = volume_[patch(part, x, angle)];
  if (!(w > 0.0)) ++wet_;
  w += v;
}

double WallFilm::wipe(double angle, std::span<const Vec3> position, std::span<const double> radius,
                      std::span<const std::uint32_t> id, std::span<double> film) {
  if (wet_ == 0) return 0.0;
  touches_.clear();
  for (std::size_t i = 0; i < position.size(); ++i) {
    for (const WallPart part : {WallPart::cylinder, WallPart::cap_low, WallPart::cap_high}) {
      if (drum_.contact(part, position[i], radius[i]).overlap > 0.0) {
        const std::size_t k = patch(part, position[i], angle);
        if (volume_[k] > 0.0) touches_.push_back({k, id[i], static_cast<std::uint32_t>(i)});
      }
    }
  }
  std::sort(touches_.begin(), touches_.end(), [](const Touch& a, const Touch& b) {
    return a.patch != b.patch ? a.patch < b.patch : a.id < b.id;
  });
  double taken = 0.0;
  for (const Touch& t : touches_) {
    double& w = volume_[t.patch];
    if (!(w > 0.0)) continue;
    const double r = radius[t.index];
    const double share = std::min(1.0, std::numbers::pi * r * r / area(t.patch));
    double take = share * w;
    if (!(w - take >= residue_)) take = w;
    film[t.index] += take;
    taken += take;
    w = take == w ? 0.0 : w - take;
    if (!(w > 0.0)) {
      w = 0.0;
      --wet_;
    }
  }
  return taken;
}

double WallFilm::volume() const {
  double sum = 0.0;
  for (const double v : volume_) sum += v;
  return sum;
}

void WallFilm::restore(std::vector<double> volume) {
  if (volume.size() != volume_.size()) {
    throw InputError(fmt::format("wall film: {} patches, the scene's wall has {}", volume.size(),
                                 volume_.size()));
  }
  wet_ = 0;
  for (const double v : volume) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      throw InputError(fmt::format("wall film: a patch holds {} m^3", v));
    }
    if (v > 0.0) ++wet_;
  }
  volume_ = std::move(volume);
}

}  // namespace drumlab
