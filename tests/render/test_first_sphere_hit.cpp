// render::first_sphere_hit, the GUI's pick: of the spheres a line of sight passes through, the one
// it enters first, against positions worked out by hand.
#include <gtest/gtest.h>

#include <vector>

#include "render/drum_view.hpp"

namespace drumlab::test {
namespace {

TEST(FirstSphereHit, TheNearestEntryWinsNotTheNearestCentre) {
  // Looking down -z from z = 10. A small sphere whose centre is nearer (z = 2, r = 0.5) and a
  // large one behind it (z = 0, r = 3): the line enters the large one first, at z = 3 > 2.5.
  const std::vector<Vec3> c = {Vec3(0.0, 0.0, 2.0), Vec3(0.0, 0.0, 0.0)};
  const std::vector<double> r = {0.5, 3.0};
  const auto hit = render::first_sphere_hit(Vec3(0.0, 0.0, 10.0), Vec3(0.0, 0.0, -10.0), c, r);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(*hit, 1u);
  // From below, the small sphere is behind the large one still: the large one is entered first.
  const auto from_below =
      render::first_sphere_hit(Vec3(0.0, 0.0, -10.0), Vec3(0.0, 0.0, 10.0), c, r);
  ASSERT_TRUE(from_below.has_value());
  EXPECT_EQ(*from_below, 1u);
}

TEST(FirstSphereHit, FrontToBackAndMisses) {
  const std::vector<Vec3> c = {Vec3(0.0, 0.0, 0.0), Vec3(0.1, 0.0, 1.0), Vec3(5.0, 0.0, 3.0)};
  const std::vector<double> r = {0.5, 0.5, 0.5};
  const Vec3 top(0.0, 0.0, 10.0), bottom(0.0, 0.0, -10.0);
  EXPECT_EQ(render::first_sphere_hit(top, bottom, c, r).value_or(9), 1u);  // z = 1 is in front
  EXPECT_EQ(render::first_sphere_hit(bottom, top, c, r).value_or(9), 0u);  // from behind: z = 0
  // Off to the side: x = 0.55 passes 0.45 from the second centre (inside) and 0.55 from the
  // first (outside).
  EXPECT_EQ(
      render::first_sphere_hit(Vec3(0.55, 0.0, -10.0), Vec3(0.55, 0.0, 10.0), c, r).value_or(9),
      1u);
  EXPECT_FALSE(render::first_sphere_hit(Vec3(2.0, 0.0, 10.0), Vec3(2.0, 0.0, -10.0), c, r));
}

}  // namespace
}  // namespace drumlab::test
