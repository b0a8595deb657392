#include "engine/block_dealer.hpp"

#include "engine/threads.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace drumlab {
namespace {

constexpr std::uint64_t kLow = 0xffffffffu;

std::uint64_t pack(std::uint64_t lo, std::uint64_t hi) {
  return lo | (hi << 32);
}

}  // namespace

void BlockDealer::deal(std::size_t n) {
#ifdef _OPENMP
#pragma omp single
#endif
  {
#ifdef _OPENMP
    const int team = omp_get_num_threads();
#else
    const int team = 1;
#endif
    const auto count = static_cast<std::size_t>((team + 1) / 2);
    if (segments_.size() != count) segments_ = std::vector<Segment>(count);
    for (std::size_t s = 0; s < count; ++s) {
      segments_[s].range.store(pack(n * s / count, n * (s + 1) / count), std::memory_order_relaxed);
    }
  }  // the barrier at the end of `single` publishes the segments to the team
}

bool BlockDealer::take_front(Segment& s, std::size_t& block) {
  std::uint64_t r = s.range.load(std::memory_order_relaxed);
  for (;;) {
    const std::uint64_t lo = r & kLow, hi = r >> 32;
    if (lo >= hi) return false;
    if (s.range.compare_exchange_weak(r, pack(lo + 1, hi), std::memory_order_relaxed)) {
      block = static_cast<std::size_t>(lo);
      return true;
    }
  }
}

bool BlockDealer::take_back(Segment& s, std::size_t& block) {
  std::uint64_t r = s.range.load(std::memory_order_relaxed);
  for (;;) {
    const std::uint64_t lo = r & kLow, hi = r >> 32;
    if (lo >= hi) return false;
    if (s.range.compare_exchange_weak(r, pack(lo, hi - 1), std::memory_order_relaxed)) {
      block = static_cast<std::size_t>(hi - 1);
      return true;
    }
  }
}

bool BlockDealer::next(std::size_t& block) {
  const int t = thread_number();
  const std::size_t count = segments_.size();
  const auto home = static_cast<std::size_t>(t / 2);
  const bool forward = t % 2 == 0;
  // The home segment first, then the others' (in turn from the next one), from the same end.
  for (std::size_t q = 0; q < count; ++q) {
    Segment& s = segments_[(home + q) % count];
    if (forward ? take_front(s, block) : take_back(s, block)) return true;
  }
  return false;
}

}  // namespace drumlab
