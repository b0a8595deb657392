#include "engine/mesh/patch_contact.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace drumlab {

NearestOnTriangle nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, TriangleFeature::vertex};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, TriangleFeature::vertex};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {a + d1 / (d1 - d3) * ab, TriangleFeature::edge};
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, TriangleFeature::vertex};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {a + d2 / (d2 - d6) * ac, TriangleFeature::edge};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return {b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b), TriangleFeature::edge};
  }
  const double denom = 1.0 / (va + vb + vc);
  return {a + ab * (vb * denom) + ac * (vc * denom), TriangleFeature::face};
}

void patch_contacts(const TriangleMesh& mesh, std::span<const Index> candidates, const Vec3& x,
                    double r, std::vector<PatchContact>& out) {
  out.clear();
  struct Best {
    double d2;
    Index triangle;
    NearestOnTriangle nearest;
  };
  std::vector<std::pair<Index, Best>> best;  // (patch, nearest so far): few patches per sphere
  const double r2 = r * r;
  for (const Index t : candidates) {
    const NearestOnTriangle q =
        nearest_on_triangle(x, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2));
    const double d2 = (x - q.point).squaredNorm();
    if (!(d2 < r2)) continue;
    const Index patch = mesh.patch[t];
    const auto it =
        std::find_if(best.begin(), best.end(), [&](const auto& b) { return b.first == patch; });
    if (it == best.end()) {
      best.push_back({patch, {d2, t, q}});
    } else if (d2 < it->second.d2 || (d2 == it->second.d2 && t < it->second.triangle)) {
      it->second = {d2, t, q};
    }
  }
  std::sort(best.begin(), best.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [patch, b] : best) {
    const double d = std::sqrt(b.d2);
    PatchContact c;
    c.patch = patch;
    c.triangle = b.triangle;
    c.feature = b.nearest.feature;
    c.point = b.nearest.point;
    c.normal = d > 0.0 ? Vec3((x - b.nearest.point) / d) : mesh.normals[b.triangle];
    c.overlap = r - d;
    out.push_back(c);
  }
}

}  // namespace drumlab
