// sort_pairs, the counting sort behind every Verlet-list build and re-ordering: checked against
// std::sort on lists large enough to be split between threads, for 1, 2 and 3 threads, and from
// inside a parallel region, where its team has one thread whatever the thread count asks.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "engine/search/search_input.hpp"
#include "engine/threads.hpp"

namespace drumlab {
namespace {

/// 150,000 distinct pairs i < j of n = 40,000 particles, shuffled; `sorted` gets them in order.
std::vector<IndexPair> shuffled_pairs(std::size_t n, std::vector<IndexPair>& sorted) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<Index> pick(0, static_cast<Index>(n - 1));
  std::set<IndexPair> unique;
  while (unique.size() < 150000) {  // distinct pairs i < j, as a search finds them
    const Index a = pick(rng), b = pick(rng);
    if (a != b) unique.insert(a < b ? IndexPair{a, b} : IndexPair{b, a});
  }
  std::vector<IndexPair> shuffled(unique.begin(), unique.end());
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  sorted.assign(unique.begin(), unique.end());
  return shuffled;
}

TEST(SortPairs, MatchesStdSortForAnyThreadCount) {
  const std::size_t n = 40000;
  std::vector<IndexPair> expected;
  const std::vector<IndexPair> shuffled = shuffled_pairs(n, expected);
  const int saved = max_threads();
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    std::vector<IndexPair> pairs = shuffled, scratch;
    std::vector<std::uint32_t> counts;
    sort_pairs(pairs, n, scratch, counts);
    EXPECT_EQ(pairs, expected) << threads << " threads";
  }
  set_thread_count(saved);
  std::vector<IndexPair> none, scratch;
  std::vector<std::uint32_t> counts;
  sort_pairs(none, n, scratch, counts);
  EXPECT_TRUE(none.empty());
}

// Inside a parallel region (nesting off, OpenMP's default) the sort's own region gets a team of
// one while the thread count still reads 2: every share must still be counted and placed.
TEST(SortPairs, SortsEverythingWithATeamSmallerThanAskedFor) {
  const std::size_t n = 40000;
  std::vector<IndexPair> expected;
  const std::vector<IndexPair> shuffled = shuffled_pairs(n, expected);
  const int saved = max_threads();
  set_thread_count(2);
  std::vector<IndexPair> pairs = shuffled, scratch;
  std::vector<std::uint32_t> counts;
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    sort_pairs(pairs, n, scratch, counts);
  }
  set_thread_count(saved);
  EXPECT_EQ(pairs.size(), expected.size());
  EXPECT_EQ(pairs, expected);
}

}  // namespace
}  // namespace drumlab
