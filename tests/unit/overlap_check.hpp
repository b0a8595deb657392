#pragma once
// Test helpers: the largest overlap r_i + r_j - |x_i - x_j| between any two spheres.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "engine/particles.hpp"

namespace drumlab::test {

/// O(N^2) over all pairs; the reference.
inline double max_overlap_brute_force(const Particles& p) {
  double worst = -1e300;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double d = (p.position[i] - p.position[j]).norm();
      worst = std::max(worst, p.radius[i] + p.radius[j] - d);
    }
  }
  return worst;
}

/// Same result for pairs that overlap (a positive value), via a hashed grid of cells 2 * max radius
/// wide; returns -1 when no pair is closer than 2 * max radius.
inline double max_overlap_grid(const Particles& p) {
  const double cell = 2.0 * p.max_radius();
  auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return (i * 73856093) ^ (j * 19349663) ^ (k * 83492791);
  };
  std::unordered_multimap<std::int64_t, std::size_t> cells;
  std::vector<std::array<std::int64_t, 3>> cell_of(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int d = 0; d < 3; ++d) {
      cell_of[i][d] = static_cast<std::int64_t>(std::floor(p.position[i][d] / cell));
    }
    cells.emplace(key(cell_of[i][0], cell_of[i][1], cell_of[i][2]), i);
  }
  double worst = -1.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& c = cell_of[i];
    for (std::int64_t dk = -1; dk <= 1; ++dk) {
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        for (std::int64_t di = -1; di <= 1; ++di) {
          auto range = cells.equal_range(key(c[0] + di, c[1] + dj, c[2] + dk));
          for (auto it = range.first; it != range.second; ++it) {
            const std::size_t j = it->second;
            if (j <= i) continue;
            const double d = (p.position[i] - p.position[j]).norm();
            worst = std::max(worst, p.radius[i] + p.radius[j] - d);
          }
        }
      }
    }
  }
  return worst;
}

}  // namespace drumlab::test
