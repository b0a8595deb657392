// sort_pairs, the counting sort behind every Verlet-list build and re-ordering: checked against
// std::sort on lists large enough to be split between threads, for 1, 2 and 3 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "engine/search/search_input.hpp"
#include "engine/threads.hpp"

namespace drumlab {
namespace {

TEST(SortPairs, MatchesStdSortForAnyThreadCount) {
  std::mt19937_64 rng(5);
  const std::size_t n = 40000;
  std::uniform_int_distribution<Index> pick(0, static_cast<Index>(n - 1));
  std::set<IndexPair> unique;
  while (unique.size() < 150000) {  // distinct pairs i < j, as a search finds them
    const Index a = pick(rng), b = pick(rng);
    if (a != b) unique.insert(a < b ? IndexPair{a, b} : IndexPair{b, a});
  }
  std::vector<IndexPair> shuffled(unique.begin(), unique.end());
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  const std::vector<IndexPair> expected(unique.begin(), unique.end());  // sorted
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

}  // namespace
}  // namespace drumlab
