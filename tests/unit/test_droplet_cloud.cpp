// Binder droplets (engine/spray/droplet_cloud.hpp): ballistic flight against the closed form,
// the laws of emission and of directions, absorption by the first particle along the path against
// a brute-force replica of every step, the liquid's accounting, periodic ends and a restart.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "engine/spray/droplet_cloud.hpp"

namespace drumlab::test {
namespace {

constexpr double kRd = 50e-6;  // droplet radius, m
const double kV = 4.0 / 3.0 * std::numbers::pi * kRd * kRd * kRd;

Drum drum(double diameter = 0.1, double depth = 0.04, bool periodic = false) {
  DrumConfig c;
  c.diameter = diameter;
  c.depth = depth;
  c.ends = periodic ? DrumEnds::periodic : DrumEnds::caps;
  return Drum(c);
}

SprayConfig nozzle(const Vec3& at, const Vec3& dir, double per_second, double angle_deg = 0.0) {
  SprayConfig s;
  s.name = "test";
  s.position = at;
  s.direction = dir;
  s.angle_deg = angle_deg;
  s.rate = per_second * kV;
  s.droplet_radius = kRd;
  s.droplet_speed = 1.0;
  return s;
}

TEST(DropletCloud, FliesBallisticallyAndIsLostAtTheWall) {
  const Vec3 g(0.0, -9.81, 0.0);
  SprayConfig s = nozzle({0.0, 0.0, 0.02}, {1.0, 0.0, 0.0}, 1000.0);  // one droplet a ms
  s.stop = 0.0015;                                                    // only the first
  DropletCloud cloud({s}, drum(), g);
  const double dt = 1e-4;
  const double born = 1e-3;
  double t = 0.0;
  bool lost = false;
  for (int n = 0; n < 2000 && !lost; ++n) {
    const SprayStep step = cloud.advance(t, dt, {}, {}, {}, {});
    t += dt;
    lost = step.lost == 1;
    if (!lost && t > born) {
      ASSERT_EQ(cloud.droplets().size(), 1u) << t;
      const double tau = t - born;
      const Vec3 exact = s.position + tau * Vec3(1.0, 0.0, 0.0) + 0.5 * tau * tau * g;
      EXPECT_NEAR((cloud.droplets()[0].position - exact).norm(), 0.0, 1e-13) << t;
      EXPECT_NEAR((cloud.droplets()[0].velocity - (Vec3(1.0, 0.0, 0.0) + tau * g)).norm(), 0.0,
                  1e-13);
    }
  }
  ASSERT_TRUE(lost);
  // It reached the wall: where the parabola meets the cylinder r = R - r_d, within one step.
  const double r = 0.05 - kRd;
  // x = tau, y = -g tau^2 / 2: x^2 + y^2 = r^2.
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (lo + hi);
    (m * m + std::pow(0.5 * 9.81 * m * m, 2) < r * r ? lo : hi) = m;
  }
  EXPECT_GE(t - born, lo);
  EXPECT_LT(t - born, lo + dt);
  const SprayTotals tot = cloud.totals();
  EXPECT_EQ(tot.emitted_count, 1u);
  EXPECT_EQ(tot.lost_count, 1u);
  EXPECT_DOUBLE_EQ(tot.sprayed, kV);
  EXPECT_DOUBLE_EQ(tot.lost, kV);
  EXPECT_FALSE(cloud.active(t));
}

TEST(DropletCloud, EmissionIsAFunctionOfTimeAndDirectionsFollowTheirLaw) {
  SprayConfig s = nozzle({0.0, 0.0, 0.02}, {0.0, -1.0, 0.0}, 20000.0, 40.0);
  s.start = 0.001;
  s.stop = 0.011;
  const DropletCloud cloud({s}, drum(), Vec3::Zero());
  EXPECT_EQ(cloud.emitted_by(0, 0.0005), 0u);
  EXPECT_EQ(cloud.emitted_by(0, 0.006), 100u);
  EXPECT_EQ(cloud.emitted_by(0, 1.0), 200u);  // stopped at 0.011
  // Two step sizes emit the same droplets in the same directions.
  for (const double dt : {1e-4, 3.7e-5}) {
    DropletCloud c({s}, drum(0.1, 0.04), Vec3::Zero());
    std::uint64_t emitted = 0;
    for (double t = 0.0; t < 0.02; t += dt) emitted += c.advance(t, dt, {}, {}, {}, {}).emitted;
    EXPECT_EQ(emitted, 200u) << dt;
  }
  // Cone: uniform over the cap's solid angle, so cos(theta) is uniform in [cos(half), 1].
  const double cos_half = std::cos(20.0 * std::numbers::pi / 180.0);
  double sum = 0.0, sum2 = 0.0;
  constexpr int kN = 20000;
  for (int k = 1; k <= kN; ++k) {
    const Vec3 d = cloud.droplet_direction(0, static_cast<std::uint64_t>(k));
    EXPECT_NEAR(d.norm(), 1.0, 1e-14);
    const double c = -d.y();
    EXPECT_GE(c, cos_half - 1e-14);
    sum += c;
    sum2 += c * c;
  }
  const double mean = sum / kN, width = 1.0 - cos_half;
  const double sd_of_mean = width / std::sqrt(12.0 * kN);
  EXPECT_NEAR(mean, 0.5 * (1.0 + cos_half), 4.0 * sd_of_mean);
  EXPECT_NEAR(sum2 / kN - mean * mean, width * width / 12.0, 0.05 * width * width / 12.0);
  // Flat fan along z: directions in the y-z plane, the angle uniform across +-half.
  SprayConfig f = s;
  f.shape = SprayShape::flat_fan;
  f.fan_axis = Vec3(0.0, 0.3, 1.0);  // its part along the direction is dropped
  const DropletCloud fan({f}, drum(), Vec3::Zero());
  double a_sum = 0.0, a_sum2 = 0.0;
  const double half = 20.0 * std::numbers::pi / 180.0;
  for (int k = 1; k <= kN; ++k) {
    const Vec3 d = fan.droplet_direction(0, static_cast<std::uint64_t>(k));
    EXPECT_NEAR(d.x(), 0.0, 1e-15);
    const double a = std::atan2(d.z(), -d.y());
    EXPECT_LE(std::abs(a), half + 1e-14);
    a_sum += a;
    a_sum2 += a * a;
  }
  EXPECT_NEAR(a_sum / kN, 0.0, 4.0 * 2.0 * half / std::sqrt(12.0 * kN));
  EXPECT_NEAR(a_sum2 / kN, half * half / 3.0, 0.05 * half * half / 3.0);
}

/// A bed of spheres in the lower half of the drum (overlaps allowed: only the droplets care).
struct Bed {
  std::vector<Vec3> x;
  std::vector<double> r, film;
  std::vector<std::uint32_t> id;
  Bed(std::size_t n, double depth, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0), rr(0.8e-3, 2e-3), z(0.0, depth);
    while (x.size() < n) {
      const Vec3 p(0.045 * u(rng), -0.045 * std::abs(u(rng)), z(rng));
      if (p.head<2>().norm() > 0.045) continue;
      x.push_back(p);
      r.push_back(rr(rng));
      id.push_back(static_cast<std::uint32_t>(n - x.size()));  // ids against storage order
    }
    film.assign(n, 0.0);
  }
};

/// The brute-force replica: every droplet against every particle, the same emission law.
struct Replica {
  const DropletCloud& law;
  Drum d;
  Vec3 g;
  std::vector<Droplet> drops;
  std::vector<std::uint64_t> emitted;
  std::uint64_t absorbed = 0, lost = 0;

  void advance(double t, double dt, Bed& bed) {
    std::vector<std::pair<Vec3, double>> start;  // position, flight time
    for (const Droplet& q : drops) start.emplace_back(q.position, dt);
    for (std::size_t s = 0; s < law.sprays().size(); ++s) {
      const SprayConfig& c = law.sprays()[s];
      const std::uint64_t target = law.emitted_by(s, t + dt);
      for (std::uint64_t k = emitted[s] + 1; k <= target; ++k) {
        const double born = c.start + static_cast<double>(k) * law.droplet_volume(s) / c.rate;
        drops.push_back({c.position, c.droplet_speed * law.droplet_direction(s, k), k,
                         static_cast<std::uint32_t>(s)});
        start.emplace_back(c.position, std::clamp(t + dt - born, 0.0, dt));
      }
      emitted[s] = std::max(emitted[s], target);
    }
    std::vector<Droplet> kept;
    for (std::size_t q = 0; q < drops.size(); ++q) {
      Droplet p = drops[q];
      const auto [a, tau] = start[q];
      p.position = a + tau * p.velocity + 0.5 * tau * tau * g;
      p.velocity += tau * g;
      const Vec3 dv = p.position - a;
      std::int64_t best = -1;
      double best_s = 2.0;
      for (std::size_t i = 0; i < bed.x.size(); ++i) {
        Vec3 f = a - bed.x[i];
        if (d.periodic()) f.z() -= d.period() * std::round(f.z() / d.period());
        const double reach = bed.r[i] + kRd;
        // Smallest s in [0, 1] with |f + s dv| <= reach, by the quadratic's smaller root.
        const double A = dv.squaredNorm(), B = 2.0 * f.dot(dv), C = f.squaredNorm() - reach * reach;
        double s = 0.0;
        if (C > 0.0) {
          const double disc = B * B - 4.0 * A * C;
          if (A == 0.0 || disc < 0.0) continue;
          s = (-B - std::sqrt(disc)) / (2.0 * A);
          if (s < 0.0 || s > 1.0) continue;
        }
        if (s < best_s || (s == best_s && bed.id[i] < bed.id[best])) {
          best_s = s;
          best = static_cast<std::int64_t>(i);
        }
      }
      if (best >= 0) {
        bed.film[best] += law.droplet_volume(p.spray);
        ++absorbed;
      } else if (d.gap(p.position, kRd) <= 0.0) {
        ++lost;
      } else {
        if (d.periodic()) p.position.z() = d.wrap_z(p.position.z());
        kept.push_back(p);
      }
    }
    drops.swap(kept);
  }
};

void expect_same_as_brute_force(bool periodic) {
  const double depth = 0.04;
  const Vec3 g(0.0, -9.81, 0.0);
  // Two nozzles above the bed: a wide cone and a flat fan along the axis, the fan's droplets
  // crossing the periodic ends when there are some.
  SprayConfig cone = nozzle({0.01, 0.02, 0.02}, {-0.2, -1.0, 0.0}, 40000.0, 60.0);
  cone.droplet_speed = 2.0;
  SprayConfig fan = nozzle({-0.01, 0.03, 0.035}, {0.0, -1.0, 0.3}, 30000.0, 90.0);
  fan.shape = SprayShape::flat_fan;
  fan.stop = 0.01;
  DropletCloud cloud({cone, fan}, drum(0.1, depth, periodic), g);
  Bed bed(1500, depth, 11);
  Bed oracle = bed;
  Replica replica{cloud, drum(0.1, depth, periodic), g, {}, {0, 0}};
  const double dt = 2e-4;  // long steps: paths of up to ~1 mm, across several particles
  std::uint64_t absorbed = 0, lost = 0;
  double t = 0.0;
  for (int n = 0; n < 150; ++n) {
    const SprayStep s = cloud.advance(t, dt, bed.x, bed.r, bed.id, bed.film);
    replica.advance(t, dt, oracle);
    t += dt;
    absorbed += s.absorbed;
    lost += s.lost;
    ASSERT_EQ(cloud.droplets().size(), replica.drops.size()) << n;
    const SprayTotals tot = cloud.totals();
    double films = 0.0;
    for (const double f : bed.film) films += f;
    EXPECT_NEAR(tot.sprayed, tot.airborne + tot.absorbed + tot.lost, 1e-12 * tot.sprayed) << n;
    EXPECT_NEAR(films, tot.absorbed, 1e-12 * tot.sprayed) << n;
  }
  EXPECT_EQ(bed.film, oracle.film);  // every droplet in the same particle
  EXPECT_EQ(absorbed, replica.absorbed);
  EXPECT_EQ(lost, replica.lost);
  EXPECT_GT(absorbed, 500u);
  EXPECT_GT(cloud.totals().emitted_count, absorbed + lost);  // some still airborne
}

TEST(DropletCloud, AbsorbedByTheFirstParticleAlongThePathAsBruteForce) {
  expect_same_as_brute_force(false);
}

TEST(DropletCloud, PeriodicEndsWrapDropletsAndTheirSearch) {
  expect_same_as_brute_force(true);
}

TEST(DropletCloud, RestoredStateContinuesBitForBit) {
  const Vec3 g(0.0, -9.81, 0.0);
  SprayConfig cone = nozzle({0.0, 0.02, 0.02}, {0.0, -1.0, 0.0}, 50000.0, 50.0);
  Bed a(800, 0.04, 5), b = a;
  DropletCloud one({cone}, drum(), g), two({cone}, drum(), g);
  const double dt = 1e-4;
  for (int n = 0; n < 60; ++n) one.advance(n * dt, dt, a.x, a.r, a.id, a.film);
  for (int n = 0; n < 30; ++n) two.advance(n * dt, dt, b.x, b.r, b.id, b.film);
  DropletCloud three({cone}, drum(), g);
  const auto counts = [](std::span<const std::uint64_t> c) {
    return std::vector<std::uint64_t>(c.begin(), c.end());
  };
  three.restore({two.droplets().begin(), two.droplets().end()}, {two.emitted(0)},
                counts(two.absorbed_counts()), counts(two.lost_counts()));
  for (int n = 30; n < 60; ++n) three.advance(n * dt, dt, b.x, b.r, b.id, b.film);
  EXPECT_EQ(a.film, b.film);
  ASSERT_EQ(one.droplets().size(), three.droplets().size());
  for (std::size_t q = 0; q < one.droplets().size(); ++q) {
    EXPECT_EQ(one.droplets()[q].position, three.droplets()[q].position);
    EXPECT_EQ(one.droplets()[q].serial, three.droplets()[q].serial);
  }
  // A state whose counts do not add up is refused.
  EXPECT_THROW(three.restore({}, {5}, {1}, {1}), InputError);
  EXPECT_THROW(three.restore({}, {1, 1}, {1}, {0}), InputError);
}

}  // namespace
}  // namespace drumlab::test
