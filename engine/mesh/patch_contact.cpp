#include "engine/mesh/patch_contact.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace drumlab {

NearestOnTriangle nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, TriangleFeature::vertex, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, TriangleFeature::vertex, 1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    return {a + d1 / (d1 - d3) * ab, TriangleFeature::edge, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, TriangleFeature::vertex, 2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    return {a + d2 / (d2 - d6) * ac, TriangleFeature::edge, 2};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return {b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b), TriangleFeature::edge, 1};
  }
  const double denom = 1.0 / (va + vb + vc);
  return {a + ab * (vb * denom) + ac * (vc * denom), TriangleFeature::face, 0};
}

namespace {

/// The welded vertices of a contact's feature: one for a vertex, two for an edge, none for a face.
std::array<Index, 2> feature_vertices(const TriangleMesh& mesh, const PatchContact& c, int& n) {
  const auto& t = mesh.triangles[c.triangle];
  const int k = c.feature_index;
  n = c.feature == TriangleFeature::vertex ? 1 : c.feature == TriangleFeature::edge ? 2 : 0;
  return {t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]};
}

/// Whether a candidate triangle of `patch` holds the feature's n vertices.
bool patch_holds(const TriangleMesh& mesh, std::span<const Index> candidates, Index patch,
                 const std::array<Index, 2>& v, int n) {
  for (const Index t : candidates) {
    if (mesh.patch[t] != patch) continue;
    const auto& c = mesh.triangles[t];
    bool all = true;
    for (int q = 0; q < n; ++q) {
      const Index w = v[static_cast<std::size_t>(q)];
      all = all && (c[0] == w || c[1] == w || c[2] == w);
    }
    if (all) return true;
  }
  return false;
}

}  // namespace

void patch_contacts(const TriangleMesh& mesh, std::span<const Index> candidates, const Vec3& x,
                    double r, std::vector<PatchContact>& out) {
  // First the nearest point per patch, with its squared distance kept in `overlap`.
  out.clear();
  const double r2 = r * r;
  for (const Index t : candidates) {
    // Farther from the triangle's plane than r: no contact (most candidates end here).
    const double plane = mesh.normals[t].dot(x - mesh.corner(t, 0));
    if (!(plane * plane < r2)) continue;
    const NearestOnTriangle q =
        nearest_on_triangle(x, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2));
    const double d2 = (x - q.point).squaredNorm();
    if (!(d2 < r2)) continue;
    const Index patch = mesh.patch[t];
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const PatchContact& c) { return c.patch == patch; });
    if (it == out.end()) {
      out.emplace_back();
      it = out.end() - 1;
    } else if (!(d2 < it->overlap || (d2 == it->overlap && t < it->triangle))) {
      continue;
    }
    *it = PatchContact{patch, t, q.feature, q.index, q.point, Vec3::Zero(), d2};
  }
  std::sort(out.begin(), out.end(),
            [](const PatchContact& a, const PatchContact& b) { return a.patch < b.patch; });
  // Then drop the edge and vertex contacts another patch already makes nearer.
  if (out.size() > 1) {
    std::size_t kept = 0;
    for (std::size_t b = 0; b < out.size(); ++b) {
      bool seen_twice = false;
      int n = 0;
      const std::array<Index, 2> v = feature_vertices(mesh, out[b], n);
      for (std::size_t a = 0; a < out.size() && n > 0 && !seen_twice; ++a) {
        if (a == b) continue;
        const bool nearer =
            out[a].overlap < out[b].overlap || (out[a].overlap == out[b].overlap && a < b);
        seen_twice = nearer && patch_holds(mesh, candidates, out[a].patch, v, n);
      }
      if (!seen_twice) out[kept++] = out[b];
    }
    out.resize(kept);
  }
  for (PatchContact& c : out) {
    const double d = std::sqrt(c.overlap);
    c.normal = d > 0.0 ? Vec3((x - c.point) / d) : mesh.normals[c.triangle];
    c.overlap = r - d;
  }
}

}  // namespace drumlab
