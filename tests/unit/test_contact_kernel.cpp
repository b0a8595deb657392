// The batched (vectorized) contact kernel: the same law as the Vec3 one, Hertz against its
// formula, and a contact's result independent of its place in a batch.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "engine/contact/contact_kernel.hpp"
#include "engine/contact/hertz_mindlin.hpp"
#include "engine/contact/rolling_resistance.hpp"
#include "engine/periodic.hpp"

namespace drumlab {
namespace {

LaneVec lane(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

void expect_near(const LaneVec& a, const Vec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x(), tol);
  EXPECT_NEAR(a.y, b.y(), tol);
  EXPECT_NEAR(a.z, b.z(), tol);
}

// Sticking, sliding, no history, history normal to the plane, and a spring without stiffness:
// each branch of the Vec3 law against the select-only LaneVec one.
TEST(ContactKernel, LaneVecTangentialLawMatchesVec3Law) {
  const MindlinTangential t{0.5};
  const Vec3 n = Vec3(0.3, -0.5, 0.81).normalized();  // no zero components
  const Vec3 a(0.7, 0.2, -0.4);
  const Vec3 b(-0.1, 0.9, 0.3);
  struct Case {
    Vec3 xi, vt;
    TangentialCoefficients c;
    double fn;
  };
  const Case cases[] = {
      {1e-6 * a, 0.01 * b, {1000.0, 0.1}, 10.0},     // sticks
      {1e-2 * a, b, {1000.0, 0.1}, 1.0},             // slides
      {Vec3::Zero(), 0.2 * b, {1000.0, 0.1}, 10.0},  // new contact
      {1e-6 * n, 0.2 * b, {1000.0, 0.1}, 10.0},      // xi along n: dropped
      {1e-3 * a, 5.0 * b, {0.0, 0.1}, 0.01},         // no spring, slides
  };
  for (const Case& k : cases) {
    Vec3 xi = k.xi;
    LaneVec xl = lane(k.xi);
    const Vec3 f = t.force(xi, n, k.vt, k.c, k.fn, 1e-4);
    const LaneVec fl = t.force(xl, lane(n), lane(k.vt), k.c, k.fn, 1e-4);
    expect_near(fl, f, 1e-14 * (1.0 + f.norm()));
    expect_near(xl, xi, 1e-16 + 1e-14 * xi.norm());
  }
}

TEST(ContactKernel, LaneVecRollingLawMatchesVec3Law) {
  const RollingResistance r{0.1};
  for (const double w : {0.0, 1e-9, 3.0}) {
    const Vec3 m = r.torque(Vec3(w, -0.5 * w, 0.7 * w), 2.0, 0.005, 1e-3);
    expect_near(r.torque(LaneVec{w, -0.5 * w, 0.7 * w}, 2.0, 0.005, 1e-3), m, 1e-15);
  }
}

// Two equal spheres pressed together at rest, no friction: F = 4/3 E* sqrt(R*) delta^{3/2}.
TEST(ContactKernel, PairBatchGivesTheHertzForce) {
  Particles p;
  const double r = 0.005;
  const double delta = 1e-4;
  p.add(Vec3(0.0, 0.0, 0.0), r, 2500.0);
  p.add(Vec3(2.0 * r - delta, 0.0, 0.0), r, 2500.0);
  const ContactLaw<HertzNormal> law{HertzNormal(2e6, 1e6, 1.0), MindlinTangential{0.0},
                                    RollingResistance{0.0}, RollingSpring{}};
  PairBatch b;
  b.add(p, 0, 1, p.position[0] - p.position[1], Vec3::Zero(), 0);
  b.evaluate<HertzNormal, false, RollingKind::none>(law, 1e-5, 1e-5);
  const double expected = 4.0 / 3.0 * 2e6 * std::sqrt(0.5 * r) * std::pow(delta, 1.5);
  EXPECT_NEAR(b.force.vec3(0).x(), -expected, 1e-12 * expected);  // pushes 0 towards -x
  EXPECT_EQ(b.force.vec3(0).y(), 0.0);
  EXPECT_EQ(b.torque_i.vec3(0), Vec3::Zero());
}

// A contact alone in a batch and the same contact among 20 others (in the vector body, not a
// tail) give the same bits: the multi-threaded force loop batches other contacts around it.
TEST(ContactKernel, ResultDoesNotDependOnThePlaceInTheBatch) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Particles p;
  const double r = 0.004;
  for (int k = 0; k < 22; ++k) {
    p.add(Vec3(0.01 * k, 0.0, 0.0), r, 2500.0);
    p.velocity.back() = Vec3(u(rng), u(rng), u(rng));
    p.omega.back() = Vec3(u(rng), u(rng), u(rng)) * 50.0;
  }
  const ContactLaw<HertzNormal> law{HertzNormal(5e6, 2e6, 0.5), MindlinTangential{0.4},
                                    RollingResistance{0.05}, RollingSpring{}};
  std::vector<Vec3> d, xi;  // overlaps of 0.5e-4 to 1.5e-4 m, slightly oblique
  for (int k = 0; k < 21; ++k) {
    d.push_back(Vec3(2.0 * r - 1e-4 * (1.0 + 0.5 * u(rng)), 1e-4 * u(rng), 0.0));
    xi.push_back(Vec3(u(rng), u(rng), 0.0) * 1e-5);
  }
  PairBatch many;
  for (int k = 0; k < 21; ++k) many.add(p, k, static_cast<Index>(k + 1), d[k], xi[k], k);
  many.evaluate<HertzNormal, true, RollingKind::torque>(law, 1e-5, 1e-5);
  for (int k : {0, 5, 17, 20}) {
    PairBatch one;
    one.add(p, k, static_cast<Index>(k + 1), d[k], xi[k], k);
    one.evaluate<HertzNormal, true, RollingKind::torque>(law, 1e-5, 1e-5);
    EXPECT_EQ(one.force.vec3(0), many.force.vec3(k)) << k;
    EXPECT_EQ(one.torque_i.vec3(0), many.torque_i.vec3(k)) << k;
    EXPECT_EQ(one.torque_j.vec3(0), many.torque_j.vec3(k)) << k;
    EXPECT_EQ(one.xi.vec3(0), many.xi.vec3(k)) << k;
    EXPECT_GT(one.force.vec3(0).norm(), 0.0);
  }
}

// gather() after add_index() (four lanes at a time where the build has AVX2) fills every lane as
// add() does, bit for bit: batches of 1 to 64 lanes (not all multiples of four), without and with
// a periodic z whose nearest image is shifted both ways.
TEST(ContactKernel, GatherFillsTheLanesAsAddDoes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double period = 0.05;
  Particles p;
  for (int k = 0; k < 40; ++k) {
    p.add(Vec3(0.01 * u(rng), 0.01 * u(rng), period * u(rng)), 0.001 + 0.002 * u(rng),
          1000.0 + 2000.0 * u(rng));
    p.velocity.back() = Vec3(u(rng), -u(rng), u(rng));
    p.omega.back() = Vec3(-u(rng), u(rng), u(rng)) * 30.0;
  }
  std::vector<Vec3> history(90);
  for (Vec3& h : history) h = Vec3(u(rng), u(rng), -u(rng)) * 1e-5;
  for (const double per : {0.0, period}) {
    int shifted = 0;
    for (const std::size_t count : {1u, 3u, 4u, 7u, 33u, 64u}) {
      PairBatch eager;
      PairBatch lazy;
      for (std::size_t l = 0; l < count; ++l) {
        const auto i = static_cast<std::size_t>(rng() % 40);
        const auto j = static_cast<Index>((i + 1 + rng() % 39) % 40);
        const std::size_t k = rng() % history.size();
        const Vec3 d = nearest_image(p.position[i], p.position[j], per);
        shifted += d.z() != p.position[i].z() - p.position[j].z();
        eager.add(p, i, j, d, history[k], k);
        lazy.add_index(i, j, k);
      }
      lazy.gather(p, history.data(), per);
      ASSERT_EQ(lazy.count, count);
      for (std::size_t l = 0; l < count; ++l) {
        EXPECT_EQ(lazy.i[l], eager.i[l]);
        EXPECT_EQ(lazy.j[l], eager.j[l]);
        EXPECT_EQ(lazy.k[l], eager.k[l]);
        EXPECT_EQ(lazy.d.vec3(l), eager.d.vec3(l)) << per << " " << l;
        EXPECT_EQ(lazy.r_i[l], eager.r_i[l]);
        EXPECT_EQ(lazy.r_j[l], eager.r_j[l]);
        EXPECT_EQ(lazy.inv_mass_sum[l], eager.inv_mass_sum[l]);
        EXPECT_EQ(lazy.inv_inertia_sum[l], eager.inv_inertia_sum[l]);
        EXPECT_EQ(lazy.v.vec3(l), eager.v.vec3(l));
        EXPECT_EQ(lazy.w_i.vec3(l), eager.w_i.vec3(l));
        EXPECT_EQ(lazy.w_j.vec3(l), eager.w_j.vec3(l));
        EXPECT_EQ(lazy.xi.vec3(l), eager.xi.vec3(l));
      }
    }
    if (per > 0.0) {
      EXPECT_GT(shifted, 10);  // the periodic case did shift images
    }
  }
}

}  // namespace
}  // namespace drumlab
