// The wall's film of binder ([[spray]] at_wall = "wet", engine/spray/wall_film.hpp): patches that
// tile the wall and turn with the drum, deposits that land where the droplet reached the wall,
// and particles touching a wet patch that take their share of it, in the order of their ids.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine/spray/droplet_cloud.hpp"
#include "engine/spray/wall_film.hpp"

namespace drumlab::test {
namespace {

constexpr double kPi = std::numbers::pi;

Drum drum(bool periodic = false) {
  DrumConfig c;
  c.diameter = 0.1;
  c.depth = 0.04;
  c.ends = periodic ? DrumEnds::periodic : DrumEnds::caps;
  return Drum(c);
}

TEST(WallFilm, PatchesTileTheWall) {
  for (const bool periodic : {false, true}) {
    const Drum d = drum(periodic);
    const WallFilm film(d, 0.004, 0.0);
    double area = 0.0;
    for (std::size_t k = 0; k < film.size(); ++k) area += film.area(k);
    const double mantle = 2.0 * kPi * 0.05 * 0.04, caps = periodic ? 0.0 : 2.0 * kPi * 0.05 * 0.05;
    EXPECT_NEAR(area, mantle + caps, 1e-12 * area) << periodic;
  }
}

TEST(WallFilm, ADepositTurnsWithTheDrumAndIsTakenWhereItWent) {
  const Drum d = drum();
  const double side = 0.004, r = 0.002;
  WallFilm film(d, side, 0.0);
  // A droplet reaches the mantle at the bottom (lab angle -pi/2) while the drum is at angle 0.
  const Vec3 bottom(0.0, -0.05 + 1e-5, 0.02);
  film.deposit(bottom, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(film.volume(), 1e-9);
  // A quarter turn later (counter-clockwise about z) that patch is at lab angle 0.
  const double quarter = 0.5 * kPi;
  const Vec3 at_bottom(0.0, -0.05 + 0.9 * r, 0.02), at_side(0.05 - 0.9 * r, 0.0, 0.02);
  EXPECT_EQ(film.patch(WallPart::cylinder, at_side, quarter),
            film.patch(WallPart::cylinder, bottom, 0.0));
  EXPECT_NE(film.patch(WallPart::cylinder, at_bottom, quarter),
            film.patch(WallPart::cylinder, bottom, 0.0));
  // A particle at the bottom takes nothing then; one at the side takes pi r^2 / A of it.
  std::vector<Vec3> x{at_bottom, at_side};
  const std::vector<double> radius{r, r};
  const std::vector<std::uint32_t> id{0, 1};
  std::vector<double> films{0.0, 0.0};
  const double taken = film.wipe(quarter, x, radius, id, films);
  const double share = kPi * r * r / film.area(film.patch(WallPart::cylinder, at_side, quarter));
  ASSERT_LT(share, 1.0);
  EXPECT_EQ(films[0], 0.0);
  EXPECT_DOUBLE_EQ(films[1], share * 1e-9);
  EXPECT_EQ(taken, films[1]);
  EXPECT_NEAR(film.volume() + films[1], 1e-9, 1e-24);
  // A particle not touching the wall takes nothing.
  x[1] = Vec3(0.04, 0.0, 0.02);
  EXPECT_EQ(film.wipe(quarter, x, radius, id, films), 0.0);
}

TEST(WallFilm, ParticlesOnOnePatchTakeInTheOrderOfTheirIdsNotOfStorage) {
  const Drum d = drum();
  WallFilm a(d, 0.004, 0.0), b(d, 0.004, 0.0);
  const Vec3 p(0.05 - 0.0005, 0.0, 0.0201), q(0.05 - 0.0005, 0.0, 0.0202);
  a.deposit(p, 0.0, 1e-9);
  b.deposit(p, 0.0, 1e-9);
  std::vector<double> fa{0.0, 0.0}, fb{0.0, 0.0};
  const std::vector<double> radius{0.001, 0.001};
  a.wipe(0.0, std::vector<Vec3>{p, q}, radius, std::vector<std::uint32_t>{7, 3}, fa);
  b.wipe(0.0, std::vector<Vec3>{q, p}, radius, std::vector<std::uint32_t>{3, 7}, fb);
  EXPECT_EQ(fa[0], fb[1]);  // id 7
  EXPECT_EQ(fa[1], fb[0]);  // id 3, first
  EXPECT_GT(fb[0], fb[1]);
}

TEST(WallFilm, CapsTakeDepositsOfDropletsThatReachThem) {
  const Drum d = drum();
  WallFilm film(d, 0.004, 0.0);
  film.deposit(Vec3(0.01, 0.0, 1e-5), 0.0, 2e-9);  // the low cap
  const std::size_t k = film.patch(WallPart::cap_low, Vec3(0.01, 0.0, 0.0), 0.0);
  EXPECT_EQ(film.patches()[k], 2e-9);
  std::vector<double> f{0.0};
  // A large particle resting on the cap there takes it all (its footprint covers the patch).
  film.wipe(0.0, std::vector<Vec3>{Vec3(0.01, 0.0, 0.0049)}, std::vector<double>{0.005},
            std::vector<std::uint32_t>{0}, f);
  EXPECT_EQ(f[0], 2e-9);
  EXPECT_EQ(film.volume(), 0.0);
}

TEST(WallFilm, RestoreChecksItsPatches) {
  WallFilm film(drum(), 0.004, 0.0);
  EXPECT_THROW(film.restore(std::vector<double>(3, 0.0)), InputError);
  std::vector<double> bad(film.size(), 0.0);
  bad[4] = -1.0;
  EXPECT_THROW(film.restore(bad), InputError);
  bad[4] = 1e-9;
  film.restore(bad);
  EXPECT_EQ(film.volume(), 1e-9);
}

// A wetting nozzle: droplets that reach the wall are walled, not lost, and the books close.
TEST(WallFilm, AWettingNozzleWallsWhatWouldBeLostAndTheBooksClose) {
  SprayConfig s;
  s.name = "wall";
  s.position = Vec3(0.0, 0.0, 0.02);
  s.direction = Vec3(1.0, 0.0, 0.0);
  s.droplet_radius = 50e-6;
  s.rate = 10000.0 * 4.0 / 3.0 * kPi * std::pow(50e-6, 3);
  s.droplet_speed = 5.0;
  SprayConfig lost = s, wet = s;
  wet.at_wall = SprayAtWall::wet;
  DropletCloud a({lost}, drum(), Vec3::Zero(), 0.004), b({wet}, drum(), Vec3::Zero(), 0.004);
  const double dt = 1e-4;
  for (int n = 0; n < 500; ++n) {
    a.advance(n * dt, dt, {}, {}, {}, {});
    b.advance(n * dt, dt, {}, {}, {}, {}, 0.3 * n * dt);
  }
  const SprayTotals ta = a.totals(), tb = b.totals();
  EXPECT_GT(ta.lost_count, 300u);
  EXPECT_EQ(tb.lost_count, 0u);
  EXPECT_EQ(tb.walled_count, ta.lost_count);
  EXPECT_NEAR(tb.on_wall, tb.walled, 1e-12 * tb.walled);
  EXPECT_NEAR(tb.sprayed, tb.airborne + tb.absorbed + tb.lost + tb.walled, 1e-12 * tb.sprayed);
  ASSERT_NE(b.wall_film(), nullptr);
  EXPECT_EQ(a.wall_film(), nullptr);
  // The state round trip: a copy restored from it continues with the same film.
  DropletCloud c({wet}, drum(), Vec3::Zero(), 0.004);
  c.restore(b.state());
  EXPECT_EQ(std::vector<double>(c.wall_film()->patches().begin(), c.wall_film()->patches().end()),
            std::vector<double>(b.wall_film()->patches().begin(), b.wall_film()->patches().end()));
  EXPECT_THROW(a.restore(b.state()), InputError);  // a wall film for a nozzle that does not wet
}

}  // namespace
}  // namespace drumlab::test
