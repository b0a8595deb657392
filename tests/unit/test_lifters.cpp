// Generated lifters (engine/mesh/lifters.hpp) and the mesh's candidate grid (mesh_grid.hpp):
// closed boxes where the spec puts them, the angled tip cupping towards the turning direction,
// one line per bad value, written as STL and read back; the grid lists every triangle a sphere
// touches (against brute force over all triangles).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "engine/mesh/lifters.hpp"
#include "engine/mesh/mesh_grid.hpp"
#include "engine/mesh/patch_contact.hpp"
#include "engine/mesh/stl_file.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Lifters, StraightBladesAreClosedBoxesStandingInFromTheMantle) {
  LifterSpec s;
  s.count = 6;
  s.height = 0.02;
  s.thickness = 0.004;
  const double R = 0.1, H = 0.05;
  const TriangleMesh m = make_mesh(lifter_triangles(s, R, H), 10.0 * kDeg, "lifters");
  EXPECT_EQ(m.size(), 6u * 12u);
  EXPECT_EQ(m.patches, 36u);  // six faces a blade
  EXPECT_TRUE(is_closed(m));
  double r_min = 1e9, r_max = 0.0;
  for (const Vec3& v : m.vertices) {
    r_min = std::min(r_min, std::hypot(v.x(), v.y()));
    r_max = std::max(r_max, std::hypot(v.x(), v.y()));
    EXPECT_GE(v.z(), 0.0);
    EXPECT_LE(v.z(), H);
  }
  EXPECT_NEAR(r_min, std::hypot(R - 0.02, 0.002), 1e-15);  // the inner face's corners
  EXPECT_GT(r_max, R);                                     // reaching into the wall
  // A ball resting on the first blade's leading face (the blade at angle 0, face at y = 0.002).
  const double r = 0.003;
  const Vec3 x(R - 0.01, 0.002 + r - 1e-4, 0.025);
  std::vector<PatchContact> out;
  std::vector<Index> all(m.size());
  for (std::size_t t = 0; t < all.size(); ++t) all[t] = static_cast<Index>(t);
  patch_contacts(m, all, x, r, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].overlap, 1e-4, 1e-15);
  EXPECT_NEAR((out[0].normal - Vec3::UnitY()).norm(), 0.0, 1e-12);
}

TEST(Lifters, AnAngledTipCupsTowardsTheTurningDirection) {
  for (const int sign : {1, -1}) {
    LifterSpec s;
    s.count = 4;
    s.height = 0.02;
    s.shape = LifterShape::angled;
    s.angle = 90.0 * kDeg;
    s.tip = 0.012;
    s.turn_sign = sign;
    const auto tris = lifter_triangles(s, 0.1, 0.05);
    EXPECT_EQ(tris.size(), 4u * 24u);
    const TriangleMesh m = make_mesh(tris, 10.0 * kDeg, "angled");
    EXPECT_TRUE(is_closed(m));
    // The first lifter (at angle 0): its tip, at the blade's inner end (x = R - h), runs to
    // y = sign * tip: the side the wall moves to.
    double y_far = 0.0;
    for (const Vec3& v : m.vertices) {
      if (v.x() > 0.0 && std::abs(v.y()) < 0.05 && v.x() < 0.1 - 0.02 + 0.003) {
        y_far = sign > 0 ? std::max(y_far, v.y()) : std::min(y_far, v.y());
      }
    }
    EXPECT_NEAR(y_far, sign * 0.012, 1e-12) << sign;  // the tip's far end, turning side
  }
}

TEST(Lifters, BadSpecsAreOneLineNamingTheKey) {
  const auto message = [](LifterSpec s) {
    try {
      lifter_triangles(s, 0.1, 0.05);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  LifterSpec s;
  s.height = 0.02;
  s.count = 0;
  EXPECT_EQ(message(s), "wall.lifters.count: must be at least 1");
  s.count = 3;
  s.height = 0.1;
  EXPECT_EQ(message(s), "wall.lifters.height: must lie in (0, R = 0.1 m)");
  s.height = 0.02;
  s.length = 0.06;
  EXPECT_EQ(message(s), "wall.lifters.length: exceeds the depth 0.05 m");
  s.length = 0.0;
  s.shape = LifterShape::angled;
  s.angle = 0.0;
  EXPECT_EQ(message(s), "wall.lifters.angle_deg: must lie in (0, 180) degrees");
}

TEST(Lifters, WrittenAsStlAndReadBack) {
  TempDir dir("lifters");
  LifterSpec s;
  s.count = 3;
  s.height = 0.02;
  const TriangleMesh m = make_mesh(lifter_triangles(s, 0.1, 0.05), 10.0 * kDeg, "lifters");
  write_stl(m, dir.path() / "lifters.stl");
  const TriangleMesh back = make_mesh(read_stl(dir.path() / "lifters.stl"), 10.0 * kDeg, "back");
  ASSERT_EQ(back.size(), m.size());
  EXPECT_EQ(back.patches, m.patches);
  for (std::size_t t = 0; t < m.size(); ++t) {
    for (int k = 0; k < 3; ++k) EXPECT_LT((back.corner(t, k) - m.corner(t, k)).norm(), 1e-8);
  }
}

TEST(MeshGrid, ListsEveryTriangleASphereTouches) {
  LifterSpec s;
  s.count = 5;
  s.height = 0.02;
  s.shape = LifterShape::angled;
  const TriangleMesh m = make_mesh(lifter_triangles(s, 0.1, 0.05), 10.0 * kDeg, "lifters");
  const double r_max = 0.003;
  const MeshGrid grid(m, 4.0 * r_max, r_max);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-0.11, 0.11), Z(-0.01, 0.06), R(0.0005, r_max);
  int touching = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 x(U(rng), U(rng), Z(rng));
    const double r = R(rng);
    const auto cand = grid.candidates(x);
    EXPECT_TRUE(std::is_sorted(cand.begin(), cand.end()));
    for (std::size_t t = 0; t < m.size(); ++t) {
      const NearestOnTriangle q =
          nearest_on_triangle(x, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2));
      if ((x - q.point).squaredNorm() < r * r) {
        ++touching;
        EXPECT_TRUE(std::binary_search(cand.begin(), cand.end(), static_cast<Index>(t)))
            << "trial " << trial << " triangle " << t;
      }
    }
  }
  EXPECT_GT(touching, 100);  // the test saw contacts
  EXPECT_TRUE(grid.candidates(Vec3(1.0, 1.0, 1.0)).empty());
}

}  // namespace
}  // namespace drumlab::test
