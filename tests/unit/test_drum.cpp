// Drum geometry: wall overlaps and normals, wall velocity, periodic wrapping, tilted gravity.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "engine/drum.hpp"

namespace drumlab {
namespace {

DrumConfig drum_config(DrumEnds ends) {
  return DrumConfig{0.9, 0.15, 1.0, 0.0, ends, {}};
}

TEST(Drum, CylinderOverlapIsRhoPlusRMinusR) {
  const Drum d(drum_config(DrumEnds::caps));
  EXPECT_DOUBLE_EQ(d.radius(), 0.45);
  const WallContact c = d.cylinder_contact(Vec3(0.3, 0.32, 0.05), 0.05);
  const double rho = std::hypot(0.3, 0.32);
  EXPECT_NEAR(c.overlap, rho + 0.05 - 0.45, 1e-15);
  EXPECT_GT(c.overlap, 0.0);
  EXPECT_NEAR((c.normal + Vec3(0.3, 0.32, 0.0) / rho).norm(), 0.0, 1e-15);
  const WallContact touch = d.cylinder_contact(Vec3(0.0, -0.43, 0.07), 0.03);
  EXPECT_NEAR(touch.overlap, 0.01, 1e-15);
  EXPECT_NEAR((touch.normal - Vec3(0, 1, 0)).norm(), 0.0, 1e-15);  // from the wall inwards
  EXPECT_LE(d.cylinder_contact(Vec3(0.1, 0.1, 0.07), 0.03).overlap, 0.0);
}

TEST(Drum, CapsTouchFromInside) {
  const Drum d(drum_config(DrumEnds::caps));
  const WallContact low = d.cap_contact(WallPart::cap_low, Vec3(0.1, 0.0, 0.02), 0.03);
  EXPECT_NEAR(low.overlap, 0.01, 1e-15);
  EXPECT_EQ(low.normal, Vec3(0, 0, 1));
  const WallContact high = d.cap_contact(WallPart::cap_high, Vec3(0.1, 0.0, 0.14), 0.03);
  EXPECT_NEAR(high.overlap, 0.02, 1e-15);
  EXPECT_EQ(high.normal, Vec3(0, 0, -1));
  EXPECT_LE(d.cap_contact(WallPart::cap_low, Vec3(0, 0, 0.075), 0.03).overlap, 0.0);
  EXPECT_LE(d.contact(WallPart::cap_high, Vec3(0, 0, 0.075), 0.03).overlap, 0.0);
}

TEST(Drum, PeriodicEndsHaveNoCapsAndWrap) {
  const Drum d(drum_config(DrumEnds::periodic));
  EXPECT_TRUE(d.periodic());
  EXPECT_LE(d.cap_contact(WallPart::cap_low, Vec3(0, 0, 0.0), 0.03).overlap, 0.0);
  EXPECT_NEAR(d.wrap_z(0.16), 0.01, 1e-15);
  EXPECT_NEAR(d.wrap_z(-0.01), 0.14, 1e-15);
  EXPECT_EQ(d.wrap_z(0.15), 0.0);
  EXPECT_EQ(d.wrap_z(0.07), 0.07);
  const double w = d.wrap_z(-1e-18);  // rounds to 0.15: must land in [0, H)
  EXPECT_GE(w, 0.0);
  EXPECT_LT(w, 0.15);
  EXPECT_TRUE(d.contains_centre(Vec3(0, 0, 5.0), 0.0));
}

TEST(Drum, WallVelocityIsOmegaZCrossR) {
  const Vec3 p(0.3, -0.2, 0.1);
  const Vec3 v = Drum::wall_velocity(p, 2.0);
  EXPECT_NEAR((v - Vec3(0, 0, 2.0).cross(p)).norm(), 0.0, 1e-15);
  // At the bottom of a drum turning about +z, the wall moves towards +x.
  EXPECT_GT(Drum::wall_velocity(Vec3(0, -0.45, 0), 1.0).x(), 0.0);
}

TEST(Drum, ContainsCentre) {
  const Drum d(drum_config(DrumEnds::caps));
  EXPECT_TRUE(d.contains_centre(Vec3(0.44, 0, 0.1), 0.0));
  EXPECT_FALSE(d.contains_centre(Vec3(0.46, 0, 0.1), 0.0));
  EXPECT_TRUE(d.contains_centre(Vec3(0.46, 0, 0.1), 0.02));
  EXPECT_FALSE(d.contains_centre(Vec3(0, 0, -0.01), 0.0));
  EXPECT_FALSE(d.contains_centre(Vec3(0, 0, 0.16), 0.0));
}

TEST(Drum, InvalidDimensionsAreInputErrors) {
  DrumConfig c = drum_config(DrumEnds::caps);
  c.diameter = 0.0;
  EXPECT_THROW(Drum{c}, InputError);
  c = drum_config(DrumEnds::caps);
  c.depth = -1.0;
  EXPECT_THROW(Drum{c}, InputError);
}

TEST(Drum, GravityIsRotatedIntoTheTiltedFrame) {
  const Vec3 g(0, -9.81, 0);
  EXPECT_NEAR((drum_frame_gravity(g, 0.0) - g).norm(), 0.0, 1e-15);
  const double t = 0.25;
  const Vec3 gd = drum_frame_gravity(g, t);
  EXPECT_NEAR(gd.norm(), 9.81, 1e-13);
  EXPECT_NEAR(gd.y(), -9.81 * std::cos(t), 1e-14);
  EXPECT_NEAR(gd.z(), 9.81 * std::sin(t), 1e-14);  // the axis descends towards +z
  EXPECT_NEAR(drum_frame_gravity(g, 0.5 * std::numbers::pi).z(), 9.81, 1e-13);
}

}  // namespace
}  // namespace drumlab
