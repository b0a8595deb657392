// The Verlet patch's partner search (engine/search/verlet_patch.hpp) against every pair tested
// by hand: each pair with a moved particle within pair_cutoff(r_a, r_b, margin), once, sorted; with
// periodic ends, with radii of three sizes, with a particle far outside the others (the grid must
// neither overflow nor miss it), and with the moved particles shared out between two threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/search/search_input.hpp"
#include "engine/search/verlet_patch.hpp"
#include "engine/threads.hpp"

namespace drumlab {
namespace {

std::vector<IndexPair> by_hand(const std::vector<Vec3>& x, const std::vector<double>& r,
                               const std::vector<Index>& moved, double margin, double period) {
  std::vector<bool> is_moved(x.size(), false);
  for (const Index f : moved) is_moved[f] = true;
  std::vector<IndexPair> out;
  for (Index a = 0; a < x.size(); ++a) {
    for (Index b = a + 1; b < x.size(); ++b) {
      if (!is_moved[a] && !is_moved[b]) continue;
      const double cut = pair_cutoff(r[a], r[b], margin);
      if (distance_squared(x[a], x[b], period) <= cut * cut) out.push_back({a, b});
    }
  }
  return out;
}

TEST(VerletPatch, FindsEveryPairOfTheMovedParticlesOnce) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double depth = 0.08;
  std::vector<Vec3> x;
  std::vector<double> r;
  for (int i = 0; i < 3000; ++i) {
    x.emplace_back(0.3 * u(rng), 0.2 * u(rng), depth * u(rng));
    r.push_back(i % 7 == 0 ? 0.015 : i % 3 == 0 ? 0.01 : 0.005);
  }
  // Far out on every axis it can be (its cells would number ~1e23 uncapped), alone.
  x.emplace_back(1.0e6, 1.0e6, 1.0e6);
  r.push_back(0.005);
  std::vector<Index> moved;
  for (Index i = 0; i < x.size(); i += 11) moved.push_back(i);
  moved.push_back(static_cast<Index>(x.size() - 1));
  const int saved = max_threads();
  for (const int threads : {1, 2}) {
    set_thread_count(threads);
    for (const double period : {0.0, depth}) {
      x.back().z() = period > 0.0 ? 0.5 * depth : 1.0e6;
      VerletPatch patch;
      std::vector<IndexPair> found;
      patch.find(x, r, moved, 0.006, period, found);
      const std::vector<IndexPair> expected = by_hand(x, r, moved, 0.006, period);
      ASSERT_GT(expected.size(), 1000u);
      EXPECT_EQ(found, expected) << threads << " threads, period " << period;
    }
  }
  set_thread_count(saved);
}

}  // namespace
}  // namespace drumlab
