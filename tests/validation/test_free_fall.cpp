// Free fall: velocity Verlet integrates a constant force exactly, so position and velocity must
// match x0 + v0 t + g t^2 / 2 and v0 + g t up to round-off (tolerance 1e-12 relative).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/drum.hpp"
#include "physics_test_helpers.hpp"

namespace drumlab {
namespace {

void expect_free_fall(double tilt) {
  SceneConfig s = test::make_scene(0.01);
  s.gravity = Vec3(0.0, -9.81, 0.0);
  s.drum = DrumConfig{4.0, 4.0, 0.0, tilt, DrumEnds::caps, {}};
  s.time.dt = 1e-4;
  Particles p;
  const Vec3 x0(0.1, 0.2, 1.5);
  const Vec3 v0(0.3, 1.0, -0.2);
  p.add(x0, 0.01, 2500.0);
  p.velocity[0] = v0;
  Simulation sim(s, std::move(p));
  const Vec3 g = sim.gravity();
  EXPECT_NEAR((g - drum_frame_gravity(s.gravity, tilt)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(g.norm(), 9.81, 1e-12);
  for (int block = 0; block < 10; ++block) {
    sim.advance(500);
    const double t = sim.time();
    const Vec3 x = x0 + v0 * t + 0.5 * g * t * t;
    const Vec3 v = v0 + g * t;
    const Particles& q = sim.particles();
    EXPECT_LE((q.position[0] - x).norm(), 1e-12 * x.norm()) << "t = " << t;
    EXPECT_LE((q.velocity[0] - v).norm(), 1e-12 * v.norm()) << "t = " << t;
  }
  EXPECT_NEAR(sim.time(), 5000 * 1e-4, 1e-12);
}

TEST(FreeFall, MatchesTheExactParabola) {
  expect_free_fall(0.0);
}

// Tilted drum: gravity in the drum frame is (0, -g cos t, g sin t): the axis descends towards +z.
TEST(FreeFall, TiltedDrumRotatesGravityIntoTheDrumFrame) {
  expect_free_fall(0.3);
  SceneConfig s = test::make_scene(0.01);
  s.gravity = Vec3(0.0, -9.81, 0.0);
  s.drum.tilt = 0.3;
  Particles p;
  p.add(Vec3(0.0, 0.0, 0.5), 0.01, 2500.0);
  Simulation sim(s, std::move(p));
  EXPECT_NEAR(sim.gravity().y(), -9.81 * std::cos(0.3), 1e-14);
  EXPECT_NEAR(sim.gravity().z(), 9.81 * std::sin(0.3), 1e-14);
  EXPECT_GT(sim.gravity().z(), 0.0);
}

}  // namespace
}  // namespace drumlab
