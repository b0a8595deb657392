#include "engine/mesh/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <numeric>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Geometry>

namespace drumlab {
namespace {

/// A position's bits, for welding corners that an STL writes identically.
std::array<std::uint64_t, 3> bits_of(const Vec3& x) {
  std::array<std::uint64_t, 3> b{};
  for (int k = 0; k < 3; ++k) {
    const double v = x[k] == 0.0 ? 0.0 : x[k];  // -0 and +0 weld
    std::memcpy(&b[static_cast<std::size_t>(k)], &v, sizeof v);
  }
  return b;
}

struct Disjoint {
  std::vector<Index> parent;
  explicit Disjoint(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  Index find(Index a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smaller root: order-independent
  }
};

/// Each undirected edge (smaller vertex first) with the triangles that have it.
std::map<std::pair<Index, Index>, std::vector<Index>> edge_triangles(const TriangleMesh& m) {
  std::map<std::pair<Index, Index>, std::vector<Index>> edges;
  for (std::size_t t = 0; t < m.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Index a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(static_cast<Index>(t));
    }
  }
  return edges;
}

}  // namespace

TriangleMesh make_mesh(const std::vector<std::array<Vec3, 3>>& corners, double smooth_angle,
                       const std::string& source) {
  TriangleMesh m;
  m.source = source;
  std::map<std::array<std::uint64_t, 3>, Index> index_of;
  for (std::size_t t = 0; t < corners.size(); ++t) {
    std::array<Index, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const Vec3& x = corners[t][static_cast<std::size_t>(k)];
      if (!x.allFinite()) {
        throw InputError(
            fmt::format("{}: triangle {} has a non-finite vertex coordinate", source, t + 1));
      }
      const auto [it, added] =
          index_of.try_emplace(bits_of(x), static_cast<Index>(m.vertices.size()));
      if (added) m.vertices.push_back(x);
      tri[static_cast<std::size_t>(k)] = it->second;
    }
    const Vec3& a = corners[t][0];
    const Vec3 n = (corners[t][1] - a).cross(corners[t][2] - a);
    const double longest =
        std::max({(corners[t][1] - a).squaredNorm(), (corners[t][2] - a).squaredNorm(),
                  (corners[t][2] - corners[t][1]).squaredNorm()});
    if (!(0.5 * n.norm() > 1e-12 * longest) || tri[0] == tri[1] || tri[1] == tri[2] ||
        tri[0] == tri[2]) {
      throw InputError(fmt::format(
          "{}: triangle {} is degenerate (its corners are (nearly) on one line)", source, t + 1));
    }
    m.triangles.push_back(tri);
    m.normals.push_back(n.normalized());
  }
  if (m.triangles.empty()) throw InputError(fmt::format("{}: the mesh has no triangle", source));
  assign_patches(m, smooth_angle);
  return m;
}

void assign_patches(TriangleMesh& m, double smooth_angle) {
  if (!(smooth_angle >= 0.0 && smooth_angle < std::numbers::pi)) {
    throw InputError(fmt::format("{}: smooth angle must lie in [0, 180) degrees", m.source));
  }
  const double cos_limit = std::cos(smooth_angle);
  Disjoint sets(m.size());
  for (const auto& [edge, tris] : edge_triangles(m)) {
    if (tris.size() != 2) continue;  // a border or a non-manifold edge: sharp
    if (m.normals[tris[0]].dot(m.normals[tris[1]]) >= cos_limit - 1e-15) {
      sets.join(tris[0], tris[1]);
    }
  }
  // Patches numbered by their first triangle: the numbering follows the file's order.
  std::map<Index, Index> number;
  m.patch.assign(m.size(), 0);
  for (std::size_t t = 0; t < m.size(); ++t) {
    const auto [it, added] =
        number.try_emplace(sets.find(static_cast<Index>(t)), static_cast<Index>(number.size()));
    m.patch[t] = it->second;
  }
  m.patches = static_cast<Index>(number.size());
}

bool is_closed(const TriangleMesh& m, std::string* why) {
  for (const auto& [edge, tris] : edge_triangles(m)) {
    bool ok = tris.size() == 2;
    if (ok) {  // opposite directions: a runs a->b in one triangle and b->a in the other
      const auto runs = [&](Index t, Index a, Index b) {
        for (int k = 0; k < 3; ++k) {
          if (m.triangles[t][k] == a && m.triangles[t][(k + 1) % 3] == b) return true;
        }
        return false;
      };
      ok = runs(tris[0], edge.first, edge.second) != runs(tris[1], edge.first, edge.second);
    }
    if (!ok) {
      if (why != nullptr) {
        const Vec3 &a = m.vertices[edge.first], &b = m.vertices[edge.second];
        *why = fmt::format(
            "the edge ({:g}, {:g}, {:g})-({:g}, {:g}, {:g}) belongs to {} triangle(s){}", a.x(),
            a.y(), a.z(), b.x(), b.y(), b.z(), tris.size(),
            tris.size() == 2 ? " running it the same way (inconsistent orientation)" : "");
      }
      return false;
    }
  }
  return true;
}

std::vector<std::array<Vec3, 3>> transformed_corners(const TriangleMesh& m, double scale,
                                                     const Eigen::Matrix3d& rotation,
                                                     const Vec3& offset) {
  std::vector<std::array<Vec3, 3>> out(m.size());
  for (std::size_t t = 0; t < m.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      out[t][static_cast<std::size_t>(k)] = rotation * (scale * m.corner(t, k)) + offset;
    }
  }
  return out;
}

double winding_number(const TriangleMesh& m, const Vec3& p) {
  double sum = 0.0;
  for (std::size_t t = 0; t < m.size(); ++t) {
    const Vec3 a = m.corner(t, 0) - p, b = m.corner(t, 1) - p, c = m.corner(t, 2) - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    sum += 2.0 * std::atan2(num, den);
  }
  return sum / (4.0 * std::numbers::pi);
}

}  // namespace drumlab
