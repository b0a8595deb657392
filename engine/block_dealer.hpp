#pragma once
// Blocks of work dealt to the threads of a team from both ends of contiguous segments, so that a
// slow thread does not hold the team up.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace drumlab {

/// Deals the blocks [0, n) to the threads of an OpenMP team. `schedule(static)` gives thread t the
/// t-th share of the blocks, and the team waits at the end for its slowest thread: on a shared
/// machine one core is often slower than the other by a quarter or more for a whole run (another
/// virtual machine on its sibling hyperthread; an efficiency core of a hybrid CPU), and then the
/// fast thread idles. `schedule(dynamic)` balances but hands neighbouring blocks to different
/// cores, whose caches then trade the partners' data. Here the blocks are cut into ceil(T / 2)
/// contiguous segments; in segment s thread 2s works forward from its start and thread 2s + 1
/// backward from its end, and the two meet where their speeds put them; a thread whose segment is
/// done takes blocks from the others' segments. Each thread works through contiguous runs of
/// blocks, and the team finishes together. Who does a block must not change what the block
/// computes (each block writes only its own outputs): then results do not depend on the dealing.
/// The segments follow the team the region got, so a team smaller than asked for (a nested
/// region, OMP_DYNAMIC) still takes every block.
///
///     BlockDealer dealer;   // outside the region; one per loop, reused
///     #pragma omp parallel
///     {
///       dealer.deal(n);   // every thread calls it; ends with the team's barrier
///       for (std::size_t b; dealer.next(b);) work(b);
///     }
class BlockDealer {
 public:
  BlockDealer() = default;
  /// A copy deals nothing yet (what is being dealt belongs to one loop's run).
  BlockDealer(const BlockDealer&) {}
  BlockDealer& operator=(const BlockDealer&) { return *this; }

  /// Starts dealing blocks [0, n) to the calling team (n < 2^32). Every thread of the team calls
  /// it, inside the parallel region, before any next(); it ends with a barrier.
  void deal(std::size_t n);
  /// The calling thread's next block: true and its number in `block`, or false when every block
  /// has been dealt.
  bool next(std::size_t& block);

 private:
  struct alignas(64) Segment {
    std::atomic<std::uint64_t> range{0};  ///< blocks [lo, hi): lo in the low 32 bits, hi above
  };
  static bool take_front(Segment& s, std::size_t& block);
  static bool take_back(Segment& s, std::size_t& block);

  std::vector<Segment> segments_;
};

/// Inside a parallel region, called by every thread of the team: deals the ranges [b size,
/// min(n, (b + 1) size)) of [0, n) and calls range(begin, end) for each of the calling thread's.
template <class Range>
void deal_ranges(BlockDealer& dealer, std::size_t n, std::size_t size, Range&& range) {
  dealer.deal((n + size - 1) / size);
  for (std::size_t b; dealer.next(b);) {
    const std::size_t begin = b * size;
    range(begin, std::min(n, begin + size));
  }
}

}  // namespace drumlab
