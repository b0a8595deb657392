#pragma once
// Triangle meshes the mesh tests build: a flat square as a grid of triangles.
#include <array>
#include <vector>

#include "engine/types.hpp"

namespace drumlab::test {

/// The square [-1, 1]^2 * half of a plane through `origin` with axes u, v (unit, orthogonal),
/// as an n x n grid of cells, two triangles each (the diagonal from the cell's low corner);
/// normals along u x v.
inline std::vector<std::array<Vec3, 3>> grid_square(int n, const Vec3& origin, const Vec3& u,
                                                    const Vec3& v, double half) {
  std::vector<std::array<Vec3, 3>> out;
  const auto at = [&](int i, int j) {
    return Vec3(origin + (-half + 2.0 * half * i / n) * u + (-half + 2.0 * half * j / n) * v);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      out.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      out.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return out;
}

}  // namespace drumlab::test
