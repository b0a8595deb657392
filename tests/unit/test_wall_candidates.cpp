// WallCandidates, the wall's Verlet list: checked against a full scan of every particle and
// wall part (the oracle), through random moves below and above the reach, motion bounds,
// re-ordering and periodic ends; and each candidate's wall parts within the reach.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "engine/contact/wall_candidates.hpp"
#include "engine/spatial_order.hpp"

namespace drumlab {
namespace {

constexpr double kRadius = 0.005;
constexpr double kReach = 0.5 * kRadius;

Particles random_particles(const Drum& drum, std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Particles p;
  while (p.size() < n) {
    const Vec3 x(u(rng) * drum.radius(), u(rng) * drum.radius(),
                 (0.5 + 0.5 * u(rng)) * drum.depth());
    // Some slightly inside the wall, as in a running drum; none deeper than a tenth of r.
    if (drum.gap(x, kRadius) > -0.1 * kRadius) p.add(x, kRadius, 2500.0);
  }
  return p;
}

// The oracle: every particle that overlaps some wall part now.
std::vector<Index> touching_wall(const Particles& p, const Drum& drum) {
  std::vector<Index> out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t part = 0; part < kWallParts; ++part) {
      if (drum.contact(static_cast<WallPart>(part), p.position[i], p.radius[i]).overlap > 0.0) {
        out.push_back(static_cast<Index>(i));
        break;
      }
    }
  }
  return out;
}

bool listed(const WallCandidates& w, Index i) {
  return std::binary_search(w.list().begin(), w.list().end(), i);
}

// The wall parts candidate i may touch (WallCandidates::parts), 0 if it is not listed.
unsigned near_parts(const WallCandidates& w, Index i) {
  const auto at = std::lower_bound(w.list().begin(), w.list().end(), i);
  if (at == w.list().end() || *at != i) return 0;
  return w.parts()[static_cast<std::size_t>(at - w.list().begin())];
}

// Every particle that touches the wall now is a candidate, with the part it touches among its
// parts.
void expect_touching_listed(const WallCandidates& w, const Particles& p, const Drum& drum) {
  for (const Index i : touching_wall(p, drum)) {
    EXPECT_TRUE(listed(w, i)) << "particle " << i << " touches the wall but is not listed";
    for (std::size_t part = 0; part < kWallParts; ++part) {
      if (drum.contact(static_cast<WallPart>(part), p.position[i], p.radius[i]).overlap > 0.0) {
        EXPECT_NE((near_parts(w, i) >> part) & 1u, 0u) << "particle " << i << " part " << part;
      }
    }
  }
}

// Particle i's gap to each wall part, computed here (not by Drum::part_gap).
double part_gap(const Drum& drum, const Particles& p, std::size_t i, std::size_t part) {
  const Vec3& x = p.position[i];
  if (part == 0) return drum.radius() - x.head<2>().norm() - p.radius[i];
  return part == 1 ? x.z() - p.radius[i] : drum.depth() - x.z() - p.radius[i];
}

// A drum, particles in it and their wall list, built.
struct Bed {
  Bed(std::uint32_t seed, DrumEnds ends, std::size_t n)
      : rng(seed), drum(DrumConfig{0.2, 0.06, 1.0, 0.0, ends, {}}) {
    p = random_particles(drum, n, rng);
    history.resize(p.size());
    w.refresh(p, drum, kReach, history);
  }
  std::mt19937 rng;
  Drum drum;
  Particles p;
  WallHistory history;
  WallCandidates w;
};

void move_all(Particles& p, double step, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Vec3& x : p.position) {
    Vec3 d(u(rng), u(rng), u(rng));
    if (d.norm() > 0.0) x += (step * u(rng)) * d.normalized();  // |move| < step
  }
}

TEST(WallCandidates, ListIsExactlyTheParticlesWithinReachAtABuild) {
  std::mt19937 rng(7);
  const Drum drum(DrumConfig{0.2, 0.06, 1.0, 0.0, DrumEnds::caps, {}});
  Particles p = random_particles(drum, 4000, rng);
  WallHistory history(p.size(), {Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3)});
  WallCandidates w;
  ASSERT_TRUE(w.refresh(p, drum, kReach, history));
  ASSERT_TRUE(std::is_sorted(w.list().begin(), w.list().end()));
  ASSERT_EQ(w.parts().size(), w.list().size());
  std::size_t near = 0;
  std::size_t one_part = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool within = drum.gap(p.position[i], kRadius) <= kReach;
    near += within;
    EXPECT_EQ(listed(w, static_cast<Index>(i)), within) << "particle " << i;
    unsigned bits = 0;
    for (std::size_t part = 0; part < kWallParts; ++part) {
      // A part within reach keeps its history; the history of any other is zeroed.
      const bool part_within = part_gap(drum, p, i, part) <= kReach;
      bits |= part_within ? 1u << part : 0u;
      EXPECT_EQ(history[i][part], part_within ? Vec3(1, 2, 3) : Vec3::Zero())
          << "particle " << i << " part " << part;
    }
    EXPECT_EQ(near_parts(w, static_cast<Index>(i)), bits) << "particle " << i;
    one_part += bits == 1u || bits == 2u || bits == 4u;
  }
  EXPECT_GT(near, 100u);
  EXPECT_LT(near, p.size() / 2) << "the list should leave out the interior";
  EXPECT_GT(one_part, near / 2) << "most candidates are near one part only";
}

TEST(WallCandidates, EveryTouchingParticleIsListedWhileMovesStayWithinTheReach) {
  Bed bed(11, DrumEnds::caps, 4000);
  auto& [rng, drum, p, history, w] = bed;
  const std::vector<Vec3> start = p.position;
  // Many small moves that add up to just under the reach from the build: no rebuild, and the
  // oracle's touching particles are all candidates (a particle's gap to the wall changes by no
  // more than it moves).
  for (int round = 0; round < 10; ++round) {
    move_all(p, 0.099 * kReach, rng);
    ASSERT_FALSE(w.refresh(p, drum, kReach, history)) << "round " << round;
    expect_touching_listed(w, p, drum);
  }
  EXPECT_EQ(w.checks(), 10u);
  // One particle beyond the reach: rebuild.
  p.position[17] = start[17] + Vec3(1.01 * kReach, 0.0, 0.0);
  EXPECT_TRUE(w.refresh(p, drum, kReach, history));
  EXPECT_EQ(w.rebuilds(), 2u);
  // A different reach or particle count rebuilds too.
  EXPECT_TRUE(w.refresh(p, drum, 2.0 * kReach, history));
}

TEST(WallCandidates, AMotionBoundSkipsTheCheckWhileItProvesNoParticleCanTouch) {
  Bed bed(13, DrumEnds::caps, 4000);
  auto& [rng, drum, p, history, w] = bed;
  const double step = 0.099 * kReach;  // each round moves every particle by less than this
  for (int round = 0; round < 10; ++round) {
    move_all(p, step, rng);
    ASSERT_FALSE(w.refresh(p, drum, kReach, history, step)) << "round " << round;
    expect_touching_listed(w, p, drum);
  }
  EXPECT_EQ(w.checks(), 0u) << "10 bounds of 0.099 reach sum to less than the reach";
  move_all(p, step, rng);
  w.refresh(p, drum, kReach, history, step);
  EXPECT_EQ(w.checks(), 1u) << "the bounds now exceed the reach: measure";
  expect_touching_listed(w, p, drum);
  // An unknown bound (infinite or NaN) always measures.
  w.refresh(p, drum, kReach, history, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(w.checks(), 2u);
}

TEST(WallCandidates, FollowsAReorderingWithoutARebuild) {
  std::mt19937 rng(3);
  const Drum drum(DrumConfig{0.2, 0.06, 1.0, 0.0, DrumEnds::caps, {}});
  Particles p = random_particles(drum, 2000, rng);
  WallHistory history(p.size());
  WallCandidates w;
  w.refresh(p, drum, kReach, history);
  // Each candidate's id with its parts: the parts move with the particle.
  std::vector<std::pair<Index, unsigned>> ids_before;
  for (std::size_t k = 0; k < w.list().size(); ++k) {
    ids_before.emplace_back(p.id[w.list()[k]], w.parts()[k]);
  }
  ReorderBuffers b;
  morton_order(p.position, 2.0 * kRadius, b);
  p.reorder(b.order, b);
  w.renumber(b.order, b.new_index);
  EXPECT_FALSE(w.refresh(p, drum, kReach, history)) << "nothing moved: no rebuild";
  ASSERT_TRUE(std::is_sorted(w.list().begin(), w.list().end()));
  ASSERT_EQ(w.parts().size(), w.list().size());
  std::vector<std::pair<Index, unsigned>> ids_after;
  for (std::size_t k = 0; k < w.list().size(); ++k) {
    ids_after.emplace_back(p.id[w.list()[k]], w.parts()[k]);
  }
  std::sort(ids_before.begin(), ids_before.end());
  std::sort(ids_after.begin(), ids_after.end());
  EXPECT_EQ(ids_after, ids_before);
  std::size_t moved = 0;
  for (std::size_t k = 0; k < w.list().size(); ++k) moved += p.id[w.list()[k]] != w.list()[k];
  EXPECT_GT(moved, 0u) << "the re-ordering should move the candidates";
}

TEST(WallCandidates, PeriodicEndsIgnoreTheAxialMotion) {
  std::mt19937 rng(5);
  const Drum drum(DrumConfig{0.2, 0.06, 1.0, 0.0, DrumEnds::periodic, {}});
  Particles p = random_particles(drum, 2000, rng);
  WallHistory history(p.size());
  WallCandidates w;
  w.refresh(p, drum, kReach, history);
  for (std::size_t i = 0; i < p.size(); ++i) {
    // No caps: only the cylinder decides.
    const double rho = p.position[i].head<2>().norm();
    const bool within = drum.radius() - rho - kRadius <= kReach;
    EXPECT_EQ(listed(w, static_cast<Index>(i)), within);
    EXPECT_EQ(near_parts(w, static_cast<Index>(i)), within ? 1u : 0u);
  }
  for (Vec3& x : p.position) x.z() = drum.wrap_z(x.z() + 0.3 * drum.depth());
  EXPECT_FALSE(w.refresh(p, drum, kReach, history));
  for (const Index i : touching_wall(p, drum)) EXPECT_TRUE(listed(w, i));
}

}  // namespace
}  // namespace drumlab
