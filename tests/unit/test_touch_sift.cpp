// The cohesive pass's sift masks (engine/contact/touch_sift.hpp) against their definitions, entry
// by entry: in the AVX-512 or AVX2 build a full chunk of 64 takes the SIMD path, shorter ones the
// scalar loop. Marks are random bytes (every combination of the three flags, and other bits
// set); states hold positive, zero, negative zero, negative, subnormal and NaN volumes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "engine/contact/touch_sift.hpp"

namespace drumlab {
namespace {

TEST(TouchSift, MasksAreTheirDefinitionsEntryByEntry) {
  std::mt19937_64 rng(11);
  const double volumes[] = {1e-12,
                            3.0,
                            0.0,
                            -0.0,
                            -1e-12,
                            std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::quiet_NaN()};
  std::uniform_int_distribution<int> byte(0, 255), pick(0, 6), offset(0, 63);
  std::size_t taken = 0, pulled = 0;
  for (int round = 0; round < 400; ++round) {
    // Unaligned starts, as the chunks of a block start at any entry.
    const std::size_t shift = static_cast<std::size_t>(offset(rng));
    std::vector<std::uint8_t> marks(64 + shift);
    std::vector<double> state(2 * (64 + shift));
    for (auto& m : marks) m = static_cast<std::uint8_t>(byte(rng));
    for (auto& s : state) s = volumes[pick(rng)];
    for (const std::size_t n : {std::size_t{64}, std::size_t{63}, std::size_t{1}, std::size_t{0}}) {
      const std::uint8_t* mark = marks.data() + shift;
      const double* s = state.data() + 2 * shift;
      const MarkMasks mm = mark_masks(mark, n);
      const std::uint64_t live = positive_even_mask(s, n);
      const std::uint64_t take = take_mask(mm, live);
      const std::uint64_t not_pulled = take_not_pulled_mask(mm, live);
      for (std::size_t q = 0; q < 64; ++q) {
        const bool in = q < n;
        const bool t = in && (mark[q] & kTouchOrEqual) != 0;
        const bool a = in && (mark[q] & kApartCentres) != 0;
        const bool o = in && (mark[q] & kOverlapping) != 0;
        const bool l = in && s[2 * q] > 0.0;
        ASSERT_EQ((mm.touch >> q) & 1, t) << "round " << round << " n " << n << " q " << q;
        ASSERT_EQ((mm.apart >> q) & 1, a) << "round " << round << " n " << n << " q " << q;
        ASSERT_EQ((mm.overlapping >> q) & 1, o) << "round " << round << " n " << n << " q " << q;
        ASSERT_EQ((live >> q) & 1, l) << "round " << round << " n " << n << " q " << q;
        ASSERT_EQ((take >> q) & 1, (t || l) && a);
        ASSERT_EQ((not_pulled >> q) & 1, ((t && !l) || (l && !o)) && a);
      }
      taken += static_cast<std::size_t>(std::popcount(take));
      pulled += static_cast<std::size_t>(std::popcount(take & ~not_pulled));
    }
  }
  // Every case occurred: entries taken, and live overlapping ones left to the pair loop.
  EXPECT_GT(taken, 1000u);
  EXPECT_GT(pulled, 100u);
}

TEST(TouchSift, BitsAreVisitedInIncreasingOrder) {
  std::vector<std::size_t> seen;
  for_each_bit((std::uint64_t{1} << 63) | (std::uint64_t{1} << 40) | 0b1011u,
               [&](std::size_t q) { seen.push_back(q); });
  EXPECT_EQ(seen, (std::vector<std::size_t>{0, 1, 3, 40, 63}));
  for_each_bit(0, [&](std::size_t) { ADD_FAILURE() << "no bit set"; });
}

}  // namespace
}  // namespace drumlab
