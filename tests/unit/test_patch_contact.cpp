// A sphere against a triangle mesh (engine/mesh/patch_contact.hpp): a flat square made of 2, 8
// and 200 triangles gives exactly one contact with the analytic plane's overlap, normal and
// contact point at every position of paths that cross inner edges and vertices, and while the
// sphere is pressed in at a vertex (to round-off: 1e-15 m, 1e-13 in the normal); a sharp fold
// gives one contact per face; the nearest point on a triangle against dense sampling.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <random>

#include "engine/mesh/patch_contact.hpp"
#include "tests/unit/mesh_test_shapes.hpp"

namespace drumlab {
namespace {

using test::grid_square;

std::vector<Index> all_triangles(const TriangleMesh& m) {
  std::vector<Index> t(m.size());
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = static_cast<Index>(k);
  return t;
}

TEST(PatchContact, AFlatSquareOfManyTrianglesActsAsOnePlane) {
  // A tilted plane, so that no coordinate is trivially zero.
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(0.3, Vec3::UnitX()) * Eigen::AngleAxisd(-0.7, Vec3::UnitY())).matrix();
  const Vec3 u = turn * Vec3::UnitX(), v = turn * Vec3::UnitY(), n = u.cross(v);
  const Vec3 origin(0.011, -0.023, 0.037);
  const double half = 0.05, r = 0.004;
  for (const int cells : {1, 2, 10}) {
    const TriangleMesh mesh = make_mesh(grid_square(cells, origin, u, v, half), 0.01, "square");
    ASSERT_EQ(mesh.size(), static_cast<std::size_t>(2 * cells * cells));
    ASSERT_EQ(mesh.patches, 1u);
    const std::vector<Index> candidates = all_triangles(mesh);
    std::vector<PatchContact> out;
    int edges = 0, vertices = 0, positions = 0;
    double worst_overlap = 0.0, worst_normal = 0.0, worst_point = 0.0;
    const auto check = [&](double a, double b, double height) {
      const Vec3 x = origin + a * u + b * v + height * n;
      patch_contacts(mesh, candidates, x, r, out);
      ASSERT_EQ(out.size(), 1u) << cells << " cells at (" << a << ", " << b << ")";
      const double plane_overlap = r - n.dot(x - origin);
      worst_overlap = std::max(worst_overlap, std::abs(out[0].overlap - plane_overlap));
      worst_normal = std::max(worst_normal, (out[0].normal - n).norm());
      worst_point = std::max(worst_point, (out[0].point - (x - n.dot(x - origin) * n)).norm());
      edges += out[0].feature == TriangleFeature::edge;
      vertices += out[0].feature == TriangleFeature::vertex;
      ++positions;
    };
    // Sliding and rolling: along the diagonal through the grid's vertices, along an inner edge
    // line, and across the cells at an angle; 0.3 mm of overlap.
    for (int k = 0; k <= 400; ++k) {
      const double s = -0.8 * half + 1.6 * half * k / 400.0;
      check(s, s, r - 3e-4);
      check(s, 0.0, r - 3e-4);
      check(s, 0.37 * s + 0.004, r - 3e-4);
    }
    // Pressed in at the square's centre (a vertex for even grids) and at a cell's corner.
    for (int k = 1; k <= 100; ++k) {
      check(0.0, 0.0, r - 1e-5 * k);
      check(2.0 * half / cells - half, 2.0 * half / cells - half, r - 1e-5 * k);
    }
    EXPECT_LT(worst_overlap, 1e-15) << cells;
    EXPECT_LT(worst_normal, 1e-13) << cells;
    EXPECT_LT(worst_point, 1e-15) << cells;
    EXPECT_GT(edges + vertices, 0) << "the paths cross inner edges and vertices";
    if (cells > 1) {
      EXPECT_GT(vertices, 0) << "and vertices";
    }
    std::printf(
        "square of %zu triangles: %d positions (%d on an edge, %d on a vertex): worst "
        "overlap %.2g m, normal %.2g, point %.2g m against the plane\n",
        mesh.size(), positions, edges, vertices, worst_overlap, worst_normal, worst_point);
  }
}

TEST(PatchContact, ASharpFoldGivesOneContactPerFace) {
  // Two squares meeting at 90 degrees along the z axis (a lifter's blade on a wall).
  const double half = 0.02, r = 0.004;
  std::vector<std::array<Vec3, 3>> tris =
      grid_square(4, Vec3(half, 0.0, 0.0), Vec3::UnitX(), Vec3::UnitZ(), half);  // the floor y = 0
  for (const auto& t : grid_square(4, Vec3(0.0, half, 0.0), Vec3::UnitZ(), Vec3::UnitY(), half)) {
    tris.push_back(t);  // the wall x = 0, its normal +x
  }
  const TriangleMesh mesh = make_mesh(tris, 10.0 * std::numbers::pi / 180.0, "fold");
  ASSERT_EQ(mesh.patches, 2u);
  std::vector<PatchContact> out;
  const Vec3 x(0.0035, 0.0037, 0.001);  // in the corner, touching both
  patch_contacts(mesh, all_triangles(mesh), x, r, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out[0].overlap, r - 0.0037, 1e-15);                   // the floor (patch 0): along +y
  EXPECT_NEAR((out[0].normal - Vec3::UnitY()).norm(), 0.0, 1e-12);  // towards the centre
  EXPECT_NEAR(out[1].overlap, r - 0.0035, 1e-15);
  EXPECT_NEAR((out[1].normal - Vec3::UnitX()).norm(), 0.0, 1e-12);
  // With a smooth angle above 90 degrees the fold is one patch: one contact, the nearer face.
  TriangleMesh smooth = mesh;
  assign_patches(smooth, 100.0 * std::numbers::pi / 180.0);
  ASSERT_EQ(smooth.patches, 1u);
  patch_contacts(smooth, all_triangles(smooth), x, r, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].overlap, r - 0.0035, 1e-15);
}

TEST(PatchContact, NearestPointOnATriangleAgainstDenseSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a(U(rng), U(rng), U(rng)), b(U(rng), U(rng), U(rng)), c(U(rng), U(rng), U(rng));
    const Vec3 p(2.0 * U(rng), 2.0 * U(rng), 2.0 * U(rng));
    const NearestOnTriangle q = nearest_on_triangle(p, a, b, c);
    double sampled = 1e300;
    const int m = 200;
    for (int i = 0; i <= m; ++i) {
      for (int j = 0; i + j <= m; ++j) {
        const Vec3 s = a + (b - a) * (double(i) / m) + (c - a) * (double(j) / m);
        sampled = std::min(sampled, (p - s).norm());
      }
    }
    const double found = (p - q.point).norm();
    EXPECT_LE(found, sampled + 1e-12) << trial;
    EXPECT_GT(found, sampled - 0.02) << trial;  // the sampling's spacing bounds the gap
  }
}

}  // namespace
}  // namespace drumlab
