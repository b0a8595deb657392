// Verlet lists over moving particles: every call must return the brute-force contact set, while
// rebuilding only when a particle has moved more than half the skin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <random>
#include <span>

#include "engine/search/verlet_list.hpp"
#include "engine/threads.hpp"

namespace drumlab {
namespace {

std::vector<IndexPair> sorted(ContactSearch& s, const SearchInput& in) {
  std::vector<IndexPair> out;
  s.find_pairs(in, out);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(VerletList, MatchesBruteForceWhileParticlesMove) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> r;
  std::vector<Vec3> v;
  for (int i = 0; i < 1500; ++i) {
    x.emplace_back(0.3 * u(rng), 0.3 * u(rng), 0.1 * u(rng));
    r.push_back(i % 3 == 0 ? 0.015 : 0.005);
    v.emplace_back(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  }
  for (const char* builder : {"m1", "m2", "m5"}) {
    auto verlet = make_search(std::string("verlet:") + builder);
    auto brute = make_search("brute");
    auto* list = dynamic_cast<VerletListSearch*>(verlet.get());
    ASSERT_NE(list, nullptr);
    std::vector<Vec3> pos = x;
    for (int step = 0; step < 60; ++step) {
      const SearchInput in{pos, r, 0.0, std::nullopt, std::nullopt};
      ASSERT_EQ(sorted(*verlet, in), sorted(*brute, in)) << builder << " step " << step;
      for (std::size_t i = 0; i < pos.size(); ++i) pos[i] += 2e-4 * v[i];  // <= 1.7e-4 m/step
    }
    // skin = 0.3 x 5 mm = 1.5 mm: a rebuild at most every ~4 steps, and at least every 9.
    EXPECT_GT(list->rebuilds(), 1u);
    EXPECT_LT(list->rebuilds(), 30u);
    EXPECT_EQ(list->calls(), 60u);
  }
}

// Called inside a parallel region (nesting off, OpenMP's default), the list's own region gets a
// team of one while the thread count reads 2: every slice of the list must still be filtered.
TEST(VerletList, FindsEveryPairWithATeamSmallerThanAskedFor) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> r(1500, 0.01);
  for (int i = 0; i < 1500; ++i) x.emplace_back(0.3 * u(rng), 0.3 * u(rng), 0.1 * u(rng));
  const SearchInput in{x, r, 0.0, std::nullopt, std::nullopt};
  auto brute = make_search("brute");
  const std::vector<IndexPair> expected = sorted(*brute, in);
  ASSERT_GT(expected.size(), 100u);
  const int saved = max_threads();
  set_thread_count(2);
  auto verlet = make_search("verlet:m2");
  std::vector<IndexPair> found;
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    found = sorted(*verlet, in);
  }
  set_thread_count(saved);
  EXPECT_EQ(found, expected);
}

// True if every pair of `contacts` is in the (sorted) list.
bool listed(std::span<const IndexPair> list, const std::vector<IndexPair>& contacts) {
  return std::all_of(contacts.begin(), contacts.end(), [&](const IndexPair& p) {
    return std::binary_search(list.begin(), list.end(), p);
  });
}

TEST(VerletList, KeepsTheListWhileTheTwoLargestMovesSumToAtMostTheSkin) {
  // Touching pairs along x, 3 cm apart: with the default skin (1 x 5 mm), no pair is within reach
  // of another but its own.
  std::vector<Vec3> x;
  std::vector<double> r(20, 0.005);
  for (int i = 0; i < 10; ++i) {
    x.emplace_back(0.03 * i, 0.0, 0.0);
    x.emplace_back(0.03 * i + 0.0101, 0.0, 0.0);
  }
  auto verlet = make_search("verlet");
  auto* list = dynamic_cast<VerletListSearch*>(verlet.get());
  auto brute = make_search("brute");
  const double skin = SearchTuning{}.verlet_skin * 0.005;
  const auto call = [&] {
    const SearchInput in{x, r, 0.0, std::nullopt, std::nullopt};
    EXPECT_EQ(sorted(*verlet, in), sorted(*brute, in));
  };
  call();
  x[3].y() += 0.8 * skin;  // the largest move: beyond half the skin, alone
  call();
  EXPECT_EQ(list->rebuilds(), 1u) << "0.8 + 0 skins: no pair can have closed the skin";
  x[8].y() -= 0.15 * skin;
  call();
  EXPECT_EQ(list->rebuilds(), 1u) << "0.8 + 0.15 skins";
  x[12].y() += 0.25 * skin;
  call();
  EXPECT_EQ(list->rebuilds(), 2u) << "0.8 + 0.25 skins: rebuild";
  EXPECT_EQ(list->checks(), 3u);
}

TEST(VerletList, AMotionBoundSkipsTheCheckAndNoContactIsLeftOut) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x;
  std::vector<double> r;
  for (int i = 0; i < 1500; ++i) {
    x.emplace_back(0.15 * (1.0 + u(rng)), 0.15 * (1.0 + u(rng)), 0.05 * (1.0 + u(rng)));
    r.push_back(i % 3 == 0 ? 0.015 : 0.005);
  }
  auto verlet = make_search("verlet:m2");
  auto* list = dynamic_cast<VerletListSearch*>(verlet.get());
  auto brute = make_search("brute");
  const double step = 1e-4;  // every particle moves by less than this per call; skin 2.5 mm
  for (int call = 0; call < 60; ++call) {
    const SearchInput in{x, r, 0.0, std::nullopt, std::nullopt};
    list->refresh(in, call == 0 ? VerletListSearch::kUnknownMotion : step);
    ASSERT_TRUE(listed(list->list(), sorted(*brute, in))) << "call " << call;
    for (Vec3& p : x) p += step * u(rng) * Vec3(u(rng), u(rng), u(rng)).normalized();
  }
  // 12 bounds of 1e-4 m sum to at most half the skin: the displacements are measured only after
  // that, and the list, rebuilt when the measured moves demand it, never misses a contact.
  EXPECT_LT(list->checks(), list->calls() - 12);
  EXPECT_GE(list->checks(), 1u);
}

TEST(VerletList, PerParticleCountersAddUpOnEveryCallAndFollowAReordering) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x, v;
  std::vector<double> r;
  for (int i = 0; i < 800; ++i) {
    x.emplace_back(0.2 * u(rng), 0.2 * u(rng), 0.05 * u(rng));
    v.emplace_back(6e-4 * (u(rng) - 0.5), 6e-4 * (u(rng) - 0.5), 0.0);  // m per call
    r.push_back(i % 2 == 0 ? 0.01 : 0.005);
  }
  auto verlet = make_search("verlet:m2");
  auto* list = dynamic_cast<VerletListSearch*>(verlet.get());
  std::vector<IndexPair> out;
  std::uint64_t rebuilds = 0;
  for (int call = 0; call < 30; ++call) {
    if (call == 15) {  // reverse the numbering, as a re-ordering would
      std::vector<Index> order(x.size()), new_index(x.size());
      for (std::size_t k = 0; k < x.size(); ++k) order[k] = static_cast<Index>(x.size() - 1 - k);
      for (std::size_t k = 0; k < x.size(); ++k) new_index[order[k]] = static_cast<Index>(k);
      std::reverse(x.begin(), x.end());
      std::reverse(v.begin(), v.end());
      std::reverse(r.begin(), r.end());
      list->renumber(order, new_index);
    }
    verlet->find_pairs({x, r, 0.0, std::nullopt, std::nullopt}, out);
    const auto tests = verlet->pairs_tested_per_particle();
    const auto cells = verlet->cells_visited_per_particle();
    EXPECT_EQ(std::accumulate(tests.begin(), tests.end(), std::uint64_t{0}),
              verlet->counters().pairs_tested)
        << "call " << call;
    EXPECT_EQ(std::accumulate(cells.begin(), cells.end(), std::uint64_t{0}),
              verlet->counters().cells_visited)
        << "call " << call;
    if (list->rebuilds() == rebuilds) {  // no rebuild: each particle tested its listed pairs
      std::vector<std::uint32_t> listed(x.size(), 0);
      for (const IndexPair& p : list->list()) ++listed[p.i];
      EXPECT_TRUE(std::ranges::equal(tests, listed)) << "call " << call;
    }
    rebuilds = list->rebuilds();
    // Still from call 12 to 17: the re-ordering at call 15 is followed by calls without a rebuild.
    if (call < 12 || call > 17) {
      for (std::size_t i = 0; i < x.size(); ++i) x[i] += v[i];
    }
  }
  EXPECT_GT(list->rebuilds(), 1u);
  EXPECT_LT(list->rebuilds(), 25u);
}

TEST(VerletList, RebuildsWhenTheInputChanges) {
  auto verlet = make_search("verlet");
  auto* list = dynamic_cast<VerletListSearch*>(verlet.get());
  std::vector<Vec3> x{Vec3(0, 0, 0), Vec3(0.021, 0, 0)};
  std::vector<double> r{0.01, 0.01};
  std::vector<IndexPair> out;
  verlet->find_pairs({x, r, 0.0, std::nullopt, std::nullopt}, out);
  EXPECT_TRUE(out.empty());
  verlet->find_pairs({x, r, 0.0, std::nullopt, std::nullopt}, out);
  EXPECT_EQ(list->rebuilds(), 1u);
  r[1] = 0.012;  // radii changed: the list must be rebuilt
  verlet->find_pairs({x, r, 0.0, std::nullopt, std::nullopt}, out);
  EXPECT_EQ(list->rebuilds(), 2u);
  EXPECT_EQ(out.size(), 1u);
  x[1].x() = 1.0;  // a jump far beyond half the skin
  verlet->find_pairs({x, r, 0.0, std::nullopt, std::nullopt}, out);
  EXPECT_EQ(list->rebuilds(), 3u);
  EXPECT_TRUE(out.empty());
}

// A bed turning as one body, with a few particles faster than the rest: in the turning frame
// (SearchInput::frame_angle) only those move, and the list is patched for them instead of
// rebuilt; it still lists every contact on every call, with and without periodic ends, with the
// motion bound given (the check skipped while the bound allows) or not. In the fixed frame each
// turn moves the outer particles by 0.6 skins: a rebuild nearly every call.
TEST(VerletList, PatchesTheParticlesThatMoveInTheTurningFrame) {
  const std::size_t n = 5000;
  ASSERT_GE(n, VerletListSearch::kPatchMinParticles);
  for (const bool periodic : {false, true}) {
    for (const bool bounded : {false, true}) {
      std::mt19937_64 rng(11);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      const double depth = 0.1;
      std::vector<Vec3> x;
      std::vector<double> r;
      while (x.size() < n) {
        const Vec3 p(0.6 * u(rng) - 0.3, 0.6 * u(rng) - 0.3, depth * u(rng));
        if (p.head<2>().norm() > 0.3) continue;
        x.push_back(p);
        r.push_back(x.size() % 4 == 0 ? 0.008 : 0.005);
      }
      const auto random_unit = [&] {
        return Vec3(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1).normalized();
      };
      std::vector<Vec3> drift(n);
      for (Vec3& d : drift) d = 5e-4 * random_unit();
      const std::optional<double> period = periodic ? std::optional<double>(depth) : std::nullopt;
      for (const bool turning : {true, false}) {
        auto verlet = make_search("verlet:m2");  // skin 1 x 5 mm
        auto* list = dynamic_cast<VerletListSearch*>(verlet.get());
        auto brute = make_search("brute");
        std::vector<Vec3> pos = x;
        const double turn = 0.01;  // rad a call: 3 mm at the rim
        double angle = 0.0;
        for (int call = 0; call < 40; ++call) {
          SearchInput in{pos, r, 0.0, std::nullopt, period};
          in.frame_angle = turning ? angle : 0.0;
          const double bound = call == 0 || !bounded ? VerletListSearch::kUnknownMotion
                                                     : 0.35 * turn + 6e-4;  // arc + drift
          list->refresh(in, bound);
          ASSERT_TRUE(listed(list->list(), sorted(*brute, in)))
              << "call " << call << (periodic ? ", periodic" : "") << (turning ? ", turning" : "");
          const double c = std::cos(turn), s = std::sin(turn);
          for (std::size_t i = 0; i < n; ++i) {
            Vec3& p = pos[i];
            // 1 in 50 drifts 0.1 skin a call along its own direction; the rest jitter a little.
            const Vec3 own = i % 50 == 0 ? drift[i] : 2e-5 * random_unit();
            p = Vec3(c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z()) + own;
            if (periodic) p.z() -= depth * std::floor(p.z() / depth);
          }
          angle += turn;
        }
        if (turning) {
          EXPECT_GT(list->patches(), 2u);
          EXPECT_LE(list->rebuilds(), 3u);
        } else {
          EXPECT_EQ(list->patches(), 0u) << "every particle moves in the fixed frame";
          EXPECT_GE(list->rebuilds(), 20u);
        }
      }
    }
  }
}

}  // namespace
}  // namespace drumlab
