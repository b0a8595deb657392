#pragma once
// A sphere against a triangle mesh: one contact per smooth patch it touches (triangle_mesh.hpp).
// On a patch the contact is the patch's point nearest the sphere's centre, found over the
// patch's triangles (face, edge or vertex of whichever triangle holds it; a tie between
// triangles, at a shared edge or vertex, goes to the lower triangle number). So a sphere on a
// flat face split into any number of triangles has one contact, with the plane's overlap and
// normal, across every inner edge and vertex: no doubled force at a shared edge, no jump at a
// vertex (the bugs users report of codes that keep one contact per triangle).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/triangle_mesh.hpp"

namespace drumlab {

enum class TriangleFeature : std::uint8_t { face, edge, vertex };

/// The point of triangle (a, b, c) nearest to p, and which feature holds it (Ericson, Real-Time
/// Collision Detection, 5.1.5: Voronoi regions of the vertices, the edges, then the face).
struct NearestOnTriangle {
  Vec3 point = Vec3::Zero();
  TriangleFeature feature = TriangleFeature::face;
  /// vertex: its corner k (0, 1, 2 for a, b, c); edge: k for the edge from corner k to corner
  /// (k + 1) mod 3; face: 0.
  std::uint8_t index = 0;
};
NearestOnTriangle nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

struct PatchContact {
  Index patch = 0;
  Index triangle = 0;  ///< the triangle that holds the contact point
  TriangleFeature feature = TriangleFeature::face;
  std::uint8_t feature_index = 0;  ///< as NearestOnTriangle::index
  Vec3 point = Vec3::Zero();       ///< on the mesh, m
  Vec3 normal = Vec3::Zero();      ///< unit, from the mesh towards the sphere's centre
  double overlap = 0.0;            ///< r - distance, > 0
};

/// The contacts of the sphere (centre x, radius r) with the triangles `candidates` of `mesh`
/// (every triangle that may touch it: the candidates of a search, or all), at most one per patch,
/// by increasing patch number. `out` is replaced (and reused: no allocation once it is large
/// enough). A centre exactly on the mesh takes the triangle's normal.
/// Across patches, an edge or vertex contact whose edge or vertex also belongs to a patch with a
/// nearer contact (or an equally near one of a lower number) is the same touch seen twice and is
/// dropped: a sphere over a sharp convex edge (a lifter's top corner) feels one force, from the
/// edge, and a sphere on a face near that edge feels only the face's. A sphere in a concave
/// corner touches both faces at two points and keeps both.
void patch_contacts(const TriangleMesh& mesh, std::span<const Index> candidates, const Vec3& x,
                    double r, std::vector<PatchContact>& out);

}  // namespace drumlab
