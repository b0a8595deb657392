// Spatial re-ordering (performance.sort_every): the Morton order is a permutation that puts
// neighbours close in memory; contact histories follow the particles (negated when a pair's order
// flips); a run that re-orders matches one that does not, particle by particle (by stable id), to
// round-off, while dropping the history would not; and every search method still gives
// bit-identical trajectories under the same sort schedule.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "engine/contact/contact_history.hpp"
#include "engine/spatial_order.hpp"
#include "engine/threads.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

TEST(MortonOrder, IsAPermutationThatKeepsNeighboursClose) {
  // A 20 x 20 x 4 lattice in random storage order.
  std::vector<Vec3> x;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 4; ++k) x.emplace_back(0.01 * i, 0.01 * j, 0.01 * k);
  std::mt19937 rng(7);
  std::shuffle(x.begin(), x.end(), rng);
  ReorderBuffers b;
  morton_order(x, 0.01, b);
  std::vector<Index> sorted = b.order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<Index> identity(x.size());
  std::iota(identity.begin(), identity.end(), 0);
  ASSERT_EQ(sorted, identity);
  for (std::size_t k = 0; k < x.size(); ++k) EXPECT_EQ(b.new_index[b.order[k]], k);
  // Mean storage distance between lattice neighbours: before (random) and after.
  auto mean_gap = [&](auto slot) {
    double sum = 0.0;
    std::size_t pairs = 0;
    for (std::size_t a = 0; a < x.size(); ++a)
      for (std::size_t c = a + 1; c < x.size(); ++c)
        if ((x[a] - x[c]).norm() < 0.0101) {
          sum += std::abs(static_cast<double>(slot(a)) - static_cast<double>(slot(c)));
          ++pairs;
        }
    return sum / static_cast<double>(pairs);
  };
  const double before = mean_gap([](std::size_t i) { return i; });
  const double after = mean_gap([&](std::size_t i) { return b.new_index[i]; });
  EXPECT_LT(after, 0.2 * before) << "before " << before << ", after " << after;
}

TEST(ContactList, RenumberKeepsEachPairsHistoryAndFlipsItsSign) {
  ContactList list;
  const std::vector<IndexPair> pairs = {{0, 1}, {0, 3}, {1, 2}, {2, 3}};
  list.update(pairs, 4);
  for (std::size_t k = 0; k < list.size(); ++k) list.history()[k] = Vec3(1.0 + k, 0.5, -0.25 * k);
  const Vec3 h01 = *list.find(0, 1), h03 = *list.find(0, 3), h12 = *list.find(1, 2),
             h23 = *list.find(2, 3);
  // Particle i moves to new_index[i]: 0 -> 3, 1 -> 0, 2 -> 2, 3 -> 1.
  const std::vector<Index> new_index = {3, 0, 2, 1};
  list.renumber(new_index);
  ASSERT_EQ(list.size(), 4u);
  ASSERT_NE(list.find(0, 3), nullptr);  // old (0, 1): flipped
  EXPECT_EQ(*list.find(0, 3), Vec3(-h01));
  ASSERT_NE(list.find(1, 3), nullptr);  // old (0, 3): flipped
  EXPECT_EQ(*list.find(1, 3), Vec3(-h03));
  ASSERT_NE(list.find(0, 2), nullptr);  // old (1, 2): same order
  EXPECT_EQ(*list.find(0, 2), h12);
  ASSERT_NE(list.find(1, 2), nullptr);  // old (2, 3): flipped
  EXPECT_EQ(*list.find(1, 2), Vec3(-h23));
  // Rows sorted, partners consistent.
  const auto row = list.row_start();
  for (std::size_t i = 0; i < list.rows(); ++i)
    for (std::size_t k = row[i] + 1; k < row[i + 1]; ++k)
      EXPECT_LT(list.col()[k - 1], list.col()[k]);
}

// The re-ordering runs on the threads at hand (the sort as runs merged along their merge path,
// the renumbering's counting sort in shares): the result must not depend on how many there are.
TEST(MortonOrder, IsTheSameForAnyThreadCount) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x(50'000);  // runs of at least 4096 keys: up to 12 threads share the sort
  for (Vec3& p : x) p = Vec3(u(rng), u(rng), 0.2 * u(rng));
  ReorderBuffers one;
  set_thread_count(1);
  morton_order(x, 0.01, one);
  for (int threads : {2, 3, 5, 8}) {
    set_thread_count(threads);
    ReorderBuffers b;
    morton_order(x, 0.01, b);
    EXPECT_EQ(b.order, one.order) << threads << " threads";
    EXPECT_EQ(b.new_index, one.new_index) << threads << " threads";
  }
  set_thread_count(1);
  for (std::size_t k = 1; k < one.keys.size(); ++k) ASSERT_LT(one.keys[k - 1], one.keys[k]);
}

TEST(ContactList, RenumberIsTheSameForAnyThreadCount) {
  // 60,000 contacts among 20,000 particles (shares of at least 16,384 entries), a random
  // permutation, then each thread count's list entry by entry.
  constexpr std::size_t n = 20'000;
  std::mt19937 rng(5);
  std::uniform_int_distribution<Index> pick(0, n - 1);
  std::vector<IndexPair> pairs;
  while (pairs.size() < 60'000) {
    const Index a = pick(rng), b = pick(rng);
    if (a != b) pairs.push_back(a < b ? IndexPair{a, b} : IndexPair{b, a});
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<Index> new_index(n);
  std::iota(new_index.begin(), new_index.end(), 0);
  std::shuffle(new_index.begin(), new_index.end(), rng);
  const auto renumbered = [&](int threads) {
    set_thread_count(threads);
    ContactList list;
    list.update(pairs, n);
    for (std::size_t k = 0; k < list.size(); ++k)
      list.history()[k] = Vec3(static_cast<double>(k), -0.5 * static_cast<double>(k), 1.0);
    list.renumber(new_index);
    set_thread_count(1);
    return list;
  };
  const ContactList one = renumbered(1);
  ASSERT_EQ(one.size(), pairs.size());
  for (int threads : {2, 3, 4}) {
    const ContactList list = renumbered(threads);
    ASSERT_TRUE(std::ranges::equal(list.row_start(), one.row_start())) << threads << " threads";
    ASSERT_TRUE(std::ranges::equal(list.col(), one.col())) << threads << " threads";
    ASSERT_TRUE(std::ranges::equal(list.history(), one.history())) << threads << " threads";
  }
  // And the entries are those of the old list under the new numbers.
  for (const IndexPair& p : pairs) {
    const Index a = new_index[p.i], b = new_index[p.j];
    ASSERT_NE(one.find(std::min(a, b), std::max(a, b)), nullptr);
  }
}

/// Positions by stable id.
std::vector<Vec3> by_id(const Particles& p) {
  std::vector<Vec3> x(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) x[p.id[i]] = p.position[i];
  return x;
}

double max_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

TEST(Reorder, RunMatchesAnUnsortedRunToRoundOff) {
  SceneConfig scene = output_scene();
  scene.performance.sort_every = 0;
  const auto settled = settled_simulation(scene, 200);
  Simulation plain(scene, settled->state());
  Simulation sorted(scene, settled->state());
  sorted.reorder_particles();
  ASSERT_NE(sorted.particles().id, plain.particles().id) << "the order should change";
  // Dropping the history instead of carrying it through the re-ordering changes the run.
  SimulationState forgetful = settled->state();
  for (Vec3& h : forgetful.contact_history) h.setZero();
  Simulation forgot(scene, std::move(forgetful));
  for (int k = 0; k < 4; ++k) {
    plain.advance(25);
    sorted.advance(25);
    forgot.advance(25);
    sorted.reorder_particles();
  }
  const double r = scene.min_radius();
  const double sorted_gap = max_difference(by_id(plain.particles()), by_id(sorted.particles()));
  const double forgot_gap = max_difference(by_id(plain.particles()), by_id(forgot.particles()));
  EXPECT_LT(sorted_gap, 1e-9 * r);
  EXPECT_GT(forgot_gap, 1e3 * sorted_gap + 1e-12 * r);
  EXPECT_EQ(sorted.diagnostics().contacts, plain.diagnostics().contacts);
}

TEST(Reorder, MethodsStayBitIdenticalUnderTheSameSchedule) {
  SceneConfig scene = output_scene();
  scene.performance.sort_every = 20;
  const auto settled = settled_simulation(scene, 50);
  std::vector<Vec3> reference;
  for (const char* method : {"m5", "verlet:m2", "m2", "verlet:mlgrid"}) {
    SCOPED_TRACE(method);
    Simulation sim(scene, settled->state());
    sim.set_search_method(method);
    sim.advance(130);
    if (reference.empty()) {
      reference = sim.particles().position;
    } else {
      EXPECT_EQ(max_difference(reference, sim.particles().position), 0.0);
    }
  }
}

}  // namespace
}  // namespace drumlab::test
