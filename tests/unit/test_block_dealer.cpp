// BlockDealer: every block dealt once for any team; contiguous runs when the threads keep pace;
// a stalled thread's blocks taken by the others.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

#include "engine/block_dealer.hpp"
#include "engine/threads.hpp"
#ifdef _OPENMP
#include <omp.h>
#endif

namespace drumlab {
namespace {

int team_size() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// The blocks each thread of a team of `team` took, in the order it took them. after_block(t,
// count) runs after thread t's count-th block, done(t) when its next() has said there are no
// more. Empty if the runtime gave a smaller team.
template <class AfterBlock, class Done>
std::vector<std::vector<std::size_t>> deal_blocks(BlockDealer& dealer, std::size_t n, int team,
                                                  AfterBlock&& after_block, Done&& done) {
  std::vector<std::vector<std::size_t>> taken(static_cast<std::size_t>(team));
  std::atomic<int> got{0};
#pragma omp parallel num_threads(team)
  {
#pragma omp single
    got = team_size();
    if (got == team) {
      dealer.deal(n);
      const int t = thread_number();
      auto& mine = taken[static_cast<std::size_t>(t)];
      for (std::size_t b; dealer.next(b);) {
        mine.push_back(b);
        after_block(t, mine.size());
      }
      done(t);
    }
  }
  if (got != team) taken.clear();
  return taken;
}

std::vector<std::vector<std::size_t>> deal_blocks(BlockDealer& dealer, std::size_t n, int team) {
  return deal_blocks(
      dealer, n, team, [](int, std::size_t) {}, [](int) {});
}

std::vector<std::size_t> sorted_union(const std::vector<std::vector<std::size_t>>& taken) {
  std::vector<std::size_t> all;
  for (const auto& t : taken) all.insert(all.end(), t.begin(), t.end());
  std::sort(all.begin(), all.end());
  return all;
}

std::vector<std::size_t> first_blocks(std::size_t n) {
  std::vector<std::size_t> v(n);
  for (std::size_t b = 0; b < n; ++b) v[b] = b;
  return v;
}

TEST(BlockDealer, DealsEveryBlockOnceForAnyTeam) {
  BlockDealer dealer;  // reused across teams and block counts, as a loop reuses it
  for (const int team : {1, 2, 3, 4, 5}) {
    for (const std::size_t n : {0, 1, 2, 3, 7, 64, 1000}) {
      const auto taken = deal_blocks(dealer, n, team);
      if (taken.empty()) GTEST_SKIP() << "the runtime gave a smaller team than " << team;
      EXPECT_EQ(sorted_union(taken), first_blocks(n)) << team << " threads, " << n << " blocks";
    }
  }
}

// Whatever the two threads' pace, each works through one contiguous run: thread 0 from the
// front, thread 1 from the back.
TEST(BlockDealer, EachThreadOfAPairTakesAContiguousRun) {
  BlockDealer dealer;
  const std::size_t n = 500;
  const auto taken = deal_blocks(dealer, n, 2);
  if (taken.empty()) GTEST_SKIP() << "the runtime gave a team of one";
  for (std::size_t q = 0; q < taken[0].size(); ++q) EXPECT_EQ(taken[0][q], q);
  for (std::size_t q = 0; q < taken[1].size(); ++q) EXPECT_EQ(taken[1][q], n - 1 - q);
  EXPECT_EQ(taken[0].size() + taken[1].size(), n);
}

// Threads that stall after their first block until the others are done (who go on only once
// every thread has its first block, so that the test does not race): with two threads,
// thread 1 takes all but thread 0's first block, from the back; with four, threads 0 and 1 (one
// segment) stall, and threads 2 and 3 finish their own segment and then take the stalled one's
// middle (thread 2 from its front, thread 3 from its back).
TEST(BlockDealer, OthersTakeTheBlocksOfStalledThreads) {
  const std::size_t n = 100;
  for (const int team : {2, 4}) {
    BlockDealer dealer;
    const int stalled = team / 2;  // threads [0, stalled) stall
    std::atomic<int> first{0}, done{0};
    const auto taken = deal_blocks(
        dealer, n, team,
        [&](int t, std::size_t count) {
          if (count != 1) return;
          ++first;
          if (t < stalled) {  // its first block taken: wait until the others are done
            while (done.load() < team - stalled) std::this_thread::yield();
          } else {  // the others go on once every thread has its first block
            while (first.load() < team) std::this_thread::yield();
          }
        },
        [&](int t) {
          if (t >= stalled) ++done;
        });
    if (taken.empty()) GTEST_SKIP() << "the runtime gave a smaller team than " << team;
    EXPECT_EQ(sorted_union(taken), first_blocks(n)) << team << " threads";
    ASSERT_EQ(taken[0].size(), 1u) << team << " threads";
    EXPECT_EQ(taken[0][0], 0u);
    if (team == 2) {
      EXPECT_EQ(taken[1].size(), n - 1);
    } else {
      ASSERT_EQ(taken[1].size(), 1u);
      EXPECT_EQ(taken[1][0], n / 2 - 1);  // the back of segment 0, [0, 50)
      EXPECT_EQ(taken[2].size() + taken[3].size(), n - 2);
      ASSERT_FALSE(taken[2].empty());
      ASSERT_FALSE(taken[3].empty());
      EXPECT_EQ(taken[2].front(), n / 2);  // segment 1 first, then segment 0's blocks
      EXPECT_EQ(taken[3].front(), n - 1);
    }
  }
}

}  // namespace
}  // namespace drumlab
