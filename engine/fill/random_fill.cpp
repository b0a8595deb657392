#include "engine/fill/random_fill.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>
#include <random>

#include <fmt/format.h>

#include "engine/mesh/mesh_wall_set.hpp"

namespace drumlab {
namespace {

constexpr int kAttemptsPerLevel = 2000;  ///< tries for one particle before the level is raised

/// Area of the segment of a circle of radius R below a chord at height h above its lowest point.
double segment_area(double R, double h) {
  h = std::clamp(h, 0.0, 2.0 * R);
  const double d = R - h;
  return R * R * std::acos(d / R) - d * std::sqrt(std::max(0.0, R * R - d * d));
}

/// Height h of the segment with the given area (bisection; area is monotone in h).
double segment_height(double R, double area) {
  if (area >= std::numbers::pi * R * R) return 2.0 * R;
  double lo = 0.0, hi = 2.0 * R;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (segment_area(R, mid) < area ? lo : hi) = mid;
  }
  return hi;
}

/// Uniform cell grid over the drum's bounding box with cells at least as wide as the largest
/// contact distance, so any overlapping particle lies in one of the 27 surrounding cells.
class OverlapGrid {
 public:
  OverlapGrid(double radius, double depth, double min_cell, std::size_t expected) {
    const double volume = 4.0 * radius * radius * depth;
    // Cells no smaller than the contact range; coarser if that would mean many more cells than
    // particles (keeps memory O(N) for tiny particles in a big drum).
    cell_ = std::max(
        min_cell, std::cbrt(volume / static_cast<double>(std::max<std::size_t>(expected, 1) * 4)));
    origin_ = Vec3(-radius, -radius, 0.0);
    n_[0] = n_[1] = std::max(1, static_cast<int>(std::ceil(2.0 * radius / cell_)));
    n_[2] = std::max(1, static_cast<int>(std::ceil(depth / cell_)));
    head_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2], -1);
  }

  bool overlaps(const Vec3& x, double r, const Particles& p) const {
    const auto c = cell_of(x);
    for (int k = std::max(0, c[2] - 1); k <= std::min(n_[2] - 1, c[2] + 1); ++k) {
      for (int j = std::max(0, c[1] - 1); j <= std::min(n_[1] - 1, c[1] + 1); ++j) {
        for (int i = std::max(0, c[0] - 1); i <= std::min(n_[0] - 1, c[0] + 1); ++i) {
          for (std::int64_t q = head_[flat(i, j, k)]; q >= 0; q = next_[q]) {
            const double reach = r + p.radius[q];
            if ((p.position[q] - x).squaredNorm() < reach * reach) return true;
          }
        }
      }
    }
    return false;
  }

  void insert(std::size_t index, const Vec3& x) {
    const auto c = cell_of(x);
    if (next_.size() <= index) next_.resize(index + 1, -1);
    auto& h = head_[flat(c[0], c[1], c[2])];
    next_[index] = h;
    h = static_cast<std::int64_t>(index);
  }

 private:
  std::array<int, 3> cell_of(const Vec3& x) const {
    std::array<int, 3> c;
    for (int d = 0; d < 3; ++d) {
      c[d] = std::clamp(static_cast<int>(std::floor((x[d] - origin_[d]) / cell_)), 0, n_[d] - 1);
    }
    return c;
  }
  std::size_t flat(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * n_[1] + j) * n_[0] + i;
  }

  double cell_ = 1.0;
  Vec3 origin_ = Vec3::Zero();
  std::array<int, 3> n_{1, 1, 1};
  std::vector<std::int64_t> head_;
  std::vector<std::int64_t> next_;
};

/// Unit vector "up" in the drum's cross-section: against the in-plane part of gravity.
Eigen::Vector2d up_direction(const Vec3& gravity) {
  const Eigen::Vector2d g(gravity.x(), gravity.y());
  if (g.norm() < 1e-12) return Eigen::Vector2d(0.0, 1.0);
  return -g.normalized();
}

/// The radii to place with their classes, largest first: small spheres fit the gaps between big
/// ones, not the other way round. A class of one radius gives `counts[c]` copies of it; a
/// distribution draws each radius from its own stream (seeded from the fill's seed), so the
/// positions' stream and every scene without a distribution stay as they were.
std::vector<std::pair<double, std::uint8_t>> planned_radii(const SceneConfig& scene,
                                                           const std::vector<std::size_t>& counts) {
  std::vector<std::size_t> order(scene.classes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return scene.classes[a].max_radius() > scene.classes[b].max_radius();
  });
  std::mt19937_64 size_rng(scene.fill.seed ^ 0x9e3779b97f4a7c15ULL);
  std::vector<std::pair<double, std::uint8_t>> plan;
  for (const std::size_t c : order) {
    const SizeDistribution size = scene.classes[c].size();
    for (std::size_t n = 0; n < counts[c]; ++n) {
      plan.emplace_back(size.draw(size_rng), static_cast<std::uint8_t>(c));
    }
  }
  std::stable_sort(plan.begin(), plan.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  return plan;
}

/// The plan's solid volume (a class of one radius: its count times one sphere, summed exactly as
/// before distributions existed, so those fills stay bit-identical).
double solid_volume(const SceneConfig& scene, const std::vector<std::size_t>& counts,
                    const std::vector<std::pair<double, std::uint8_t>>& plan) {
  double v = 0.0;
  for (std::size_t c = 0; c < counts.size(); ++c) {
    if (scene.classes[c].polydisperse()) {
      for (const auto& [r, k] : plan) {
        if (static_cast<std::size_t>(k) == c) v += 4.0 / 3.0 * std::numbers::pi * r * r * r;
      }
    } else {
      const double r = scene.classes[c].radius;
      v += static_cast<double>(counts[c]) * 4.0 / 3.0 * std::numbers::pi * r * r * r;
    }
  }
  return v;
}

/// The drum's cross-section seen from gravity: "up" against its in-plane part.
struct CrossSection {
  explicit CrossSection(const SceneConfig& scene)
      : up(up_direction(scene.gravity)),
        side(up.y(), -up.x()),
        R(0.5 * scene.drum.diameter),
        H(scene.drum.depth) {}

  /// Uniform random centre of a sphere of radius r inside the drum (one radius from the mantle
  /// and the end planes) and below `level`, measured from the axis along `up`.
  Vec3 sample_centre(double r, double level, std::mt19937_64& rng) const {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double reach = R - r;
    const double top = std::clamp(level, -reach + 0.5 * r, reach);
    // Half-width of the disc of radius `reach` at the level `top`: the segment's widest chord.
    const double half = top >= 0.0 ? reach : std::sqrt(reach * reach - top * top);
    Eigen::Vector2d q;
    do {
      const double u = -reach + unit(rng) * (top + reach);
      const double s = -half + unit(rng) * 2.0 * half;
      q = u * up + s * side;
    } while (q.squaredNorm() > reach * reach);
    return Vec3(q.x(), q.y(), r + unit(rng) * (H - 2.0 * r));
  }

  Eigen::Vector2d up, side;
  double R, H;
};

}  // namespace

std::vector<std::size_t> class_counts(const SceneConfig& scene) {
  const auto& classes = scene.classes;
  if (classes.empty())
    throw InputError(fmt::format("{}: particles: no size classes", scene.source));
  const double rmax = scene.max_radius();
  std::vector<double> weight(classes.size());
  for (std::size_t c = 0; c < classes.size(); ++c) {
    // Scaled, so weights are O(1); a distribution's particles have the mean volume E[r^3].
    const double s = classes[c].radius / rmax;
    const double cube = classes[c].polydisperse()
                            ? classes[c].size().mean_cube() / (rmax * rmax * rmax)
                            : s * s * s;
    weight[c] = classes[c].volume_fraction / cube;
  }
  const double total = std::accumulate(weight.begin(), weight.end(), 0.0);
  const auto n = static_cast<double>(scene.fill.count);
  std::vector<std::size_t> counts(classes.size());
  std::vector<double> remainder(classes.size());
  std::size_t assigned = 0;
  for (std::size_t c = 0; c < classes.size(); ++c) {
    const double exact = n * weight[c] / total;
    // Round values within 1e-9 of an integer to it, so exact splits do not depend on rounding.
    const double near = std::round(exact);
    const double base =
        std::abs(exact - near) < 1e-9 * std::max(1.0, exact) ? near : std::floor(exact);
    counts[c] = static_cast<std::size_t>(base);
    remainder[c] = exact - base;
    assigned += counts[c];
  }
  std::vector<std::size_t> order(classes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return remainder[a] > remainder[b]; });
  for (std::size_t k = 0; assigned < scene.fill.count; k = (k + 1) % order.size()) {
    ++counts[order[k]];
    ++assigned;
  }
  return counts;
}

Particles random_fill(const SceneConfig& scene) {
  if (scene.fill.kind != FillKind::random) {
    throw InputError(
        fmt::format("{}: fill.kind: random_fill needs kind = \"random\"", scene.source));
  }
  const auto counts = class_counts(scene);
  const std::size_t total = scene.fill.count;
  const CrossSection drum(scene);
  // Level of the fill region: a circular segment of the cross-section times the depth.
  const auto plan = planned_radii(scene, counts);
  const double region_volume = solid_volume(scene, counts, plan) / scene.fill.volume_fraction;
  double level = -drum.R + segment_height(drum.R, region_volume / drum.H);

  Particles p;
  p.reserve(total);
  OverlapGrid grid(drum.R, drum.H, 2.0 * scene.max_radius(), total);
  std::mt19937_64 rng(scene.fill.seed);
  // Triangle walls (lifters, inserts): no particle on or inside one. Without, nothing changes.
  std::optional<MeshWallSet> meshes;
  if (scene.has_meshes()) {
    meshes.emplace(build_wall_meshes(scene), 2.0 * scene.max_radius(), scene.max_radius());
  }
  MeshWallSet::Scratch scratch;
  std::vector<MeshContact> hits;
  for (const auto& [r, c] : plan) {
    for (;;) {
      std::optional<Vec3> x;
      for (int attempt = 0; attempt < kAttemptsPerLevel && !x; ++attempt) {
        x = drum.sample_centre(r, level, rng);
        if (grid.overlaps(*x, r, p) || (meshes && meshes->blocks(*x, r, scratch, hits))) {
          x.reset();
        }
      }
      if (x) {
        grid.insert(p.size(), *x);
        p.add(*x, r, scene.material.density, c);
        break;
      }
      if (level >= drum.R - r) {
        throw InputError(fmt::format(
            "{}: fill: cannot place {} of {} particles (radius {} m) anywhere in the drum; "
            "lower fill.count or fill.volume_fraction",
            scene.source, total - p.size(), total, r));
      }
      level += 0.02 * scene.drum.diameter;  // no room left below the level: raise it
    }
  }
  return p;
}

}  // namespace drumlab
