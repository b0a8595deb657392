// The paper's static cubic packing: counts per class, lattice positions, order, no overlaps.
#include <gtest/gtest.h>

#include <array>

#include "engine/fill/paper_packing.hpp"
#include "overlap_check.hpp"

namespace drumlab {
namespace {

std::array<std::size_t, 3> counts_by_class(const Particles& p) {
  std::array<std::size_t, 3> n{};
  for (auto c : p.size_class) ++n.at(c);
  return n;
}

/// Largest amount by which a sphere leaves its strip of the box (<= 0 when all are inside).
double max_protrusion(const Particles& p, const Vec3& box) {
  double worst = -1e300;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    const double r = p.radius[i];
    const double y0 = p.size_class[i] * box.y() / 3.0;
    const Vec3 lo(0.0, y0, 0.0), hi(box.x(), y0 + box.y() / 3.0, box.z());
    for (int d = 0; d < 3; ++d) worst = std::max({worst, lo[d] - (x[d] - r), x[d] + r - hi[d]});
  }
  return worst;
}

TEST(PaperPacking, ShallowBoxCountsPerClass) {
  const Vec3 box(1.85, 1.80, 0.15);
  const std::array<std::size_t, 3> expected{185u * 60 * 15, 92u * 30 * 7, 61u * 20 * 5};
  EXPECT_EQ(paper_packing_counts(box), expected);
  const Particles p = paper_packing(box, 2500.0);
  EXPECT_EQ(counts_by_class(p), expected);
  EXPECT_EQ(p.size(), 166500u + 19320u + 6100u);
  EXPECT_LE(max_protrusion(p, box), 1e-12);
}

TEST(PaperPacking, DeepBoxCountsPerClass) {
  const Vec3 box(1.85, 1.80, 2.0);
  const std::array<std::size_t, 3> expected{185u * 60 * 200, 92u * 30 * 100, 61u * 20 * 66};
  EXPECT_EQ(paper_packing_counts(box), expected);
  const Particles p = paper_packing(box, 2500.0);
  EXPECT_EQ(counts_by_class(p), expected);
  EXPECT_EQ(p.size(), 2576520u);
  EXPECT_LE(max_protrusion(p, box), 1e-12);
}

TEST(PaperPacking, LatticeOrderXThenZThenY) {
  const Vec3 box(1.85, 1.80, 0.15);
  const Particles p = paper_packing(box, 2500.0);
  const double r = 0.005;
  EXPECT_EQ(p.position[0], Vec3(r, r, r));
  EXPECT_EQ(p.position[1], Vec3(3 * r, r, r));
  EXPECT_EQ(p.position[184], Vec3(369 * r, r, r));
  EXPECT_EQ(p.position[185], Vec3(r, r, 3 * r));       // z next
  EXPECT_EQ(p.position[185 * 15], Vec3(r, 3 * r, r));  // then y
  const std::size_t first_medium = 166500;
  EXPECT_EQ(p.size_class[first_medium - 1], 0);
  EXPECT_EQ(p.size_class[first_medium], 1);
  EXPECT_EQ(p.radius[first_medium], 0.010);
  EXPECT_NEAR((p.position[first_medium] - Vec3(0.010, 0.610, 0.010)).norm(), 0.0, 1e-15);
  const std::size_t first_large = first_medium + 19320;
  EXPECT_EQ(p.radius[first_large], 0.015);
  EXPECT_NEAR((p.position[first_large] - Vec3(0.015, 1.215, 0.015)).norm(), 0.0, 1e-15);
  // Neighbours along x touch: spacing is one diameter.
  EXPECT_NEAR((p.position[first_large + 1] - p.position[first_large]).norm(), 0.030, 1e-15);
  for (std::size_t i = 0; i < p.size(); ++i) ASSERT_EQ(p.id[i], i);
}

TEST(PaperPacking, NoOverlapsInTheShallowBox) {
  const Particles p = paper_packing(Vec3(1.85, 1.80, 0.15), 2500.0);
  const double worst = test::max_overlap_grid(p);
  EXPECT_LE(worst, 1e-9);
  EXPECT_GE(worst, -1e-9);  // touching spheres, as in a simple cubic packing
}

TEST(PaperPacking, SmallBoxBruteForce) {
  const Vec3 box(0.2, 0.18, 0.07);  // strips of 0.06 m
  const Particles p = paper_packing(box, 2500.0);
  const std::array<std::size_t, 3> expected{20u * 6 * 7, 10u * 3 * 3, 6u * 2 * 2};
  EXPECT_EQ(counts_by_class(p), expected);
  const double worst = test::max_overlap_brute_force(p);
  EXPECT_LE(worst, 1e-9);
  EXPECT_GE(worst, -1e-9);
  EXPECT_LE(max_protrusion(p, box), 1e-12);
}

TEST(PaperPacking, InvalidInput) {
  EXPECT_THROW(paper_packing(Vec3(1.0, 0.0, 1.0), 2500.0), InputError);
  EXPECT_THROW(paper_packing(Vec3(1.0, 1.0, -1.0), 2500.0), InputError);
  EXPECT_THROW(paper_packing(Vec3(1.0, 1.0, 1.0), 0.0), InputError);
  EXPECT_THROW(paper_packing(Vec3(1.0, 1.0, 1.0), {0.01, -0.02, 0.03}, 2500.0), InputError);
}

}  // namespace
}  // namespace drumlab
