// The pair loop's split of a chunk (engine/contact/pair_split.hpp) against its scalar definitions,
// entry by entry: in the AVX-512 or AVX2 build groups of 8 or 4 take the SIMD path, a tail the
// scalar loop. Squared distances below, equal to and just around the radii's squared sum, zero,
// negative zero, NaN on either side, infinity; chunk lengths 64, 63, 5, 1 and 0. And the zeroing of
// the entries that do not overlap (zero_triples).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "engine/contact/pair_split.hpp"

namespace drumlab {
namespace {

TEST(PairSplit, ChunkIsItsEntriesTestsEntryByEntry) {
  std::mt19937_64 rng(17);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double tolerance = 1e-9;
  std::uniform_int_distribution<int> pick(0, 11);
  std::uniform_real_distribution<double> radii(1e-4, 2e-3);
  std::size_t counts[5] = {0, 0, 0, 0, 0};  // overlapping, touching, the three mark flags
  for (int round = 0; round < 400; ++round) {
    std::vector<double> dist2(64), sum_r(64);
    for (std::size_t q = 0; q < 64; ++q) {
      sum_r[q] = radii(rng);
      const double s2 = sum_r[q] * sum_r[q];
      const double cut = (sum_r[q] + tolerance) * (sum_r[q] + tolerance);
      const double cases[] = {0.5 * s2,
                              s2,
                              2.0 * s2,
                              0.0,
                              -0.0,
                              nan,
                              inf,
                              std::nextafter(s2, 0.0),
                              std::nextafter(s2, inf),
                              cut,
                              std::nextafter(cut, inf),
                              1e-300};
      dist2[q] = cases[pick(rng)];
      if (pick(rng) == 0) sum_r[q] = pick(rng) < 6 ? nan : 0.0;
    }
    for (const std::size_t n :
         {std::size_t{64}, std::size_t{63}, std::size_t{5}, std::size_t{1}, std::size_t{0}}) {
      std::vector<std::uint8_t> mark(65, 0xEE);  // the entry past n stays untouched
      const PairSplit marked =
          split_pairs<true>(dist2.data(), sum_r.data(), n, tolerance, mark.data());
      const PairSplit plain = split_pairs<false>(dist2.data(), sum_r.data(), n, tolerance, nullptr);
      std::size_t touching = 0;
      for (std::size_t q = 0; q < 64; ++q) {
        const bool in = q < n;
        const double d = dist2[q], r = sum_r[q];
        const bool overlaps = in && d < r * r && d != 0.0;
        ASSERT_EQ((marked.overlapping >> q) & 1, overlaps) << "round " << round << " q " << q;
        ASSERT_EQ((plain.overlapping >> q) & 1, overlaps) << "round " << round << " q " << q;
        if (!in) continue;
        touching += d <= (r + tolerance) * (r + tolerance);
        ASSERT_EQ(mark[q], touch_mark(d, r))
            << "round " << round << " n " << n << " q " << q << " dist2 " << d << " sum_r " << r;
        counts[0] += overlaps;
        for (int f = 0; f < 3; ++f) counts[2 + f] += (mark[q] >> f) & 1;
      }
      EXPECT_EQ(marked.touching, touching) << "round " << round << " n " << n;
      EXPECT_EQ(plain.touching, touching) << "round " << round << " n " << n;
      EXPECT_EQ(mark[n], 0xEE) << "n " << n;
      counts[1] += touching;
      EXPECT_EQ(first_bits(n), n == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1);
    }
  }
  for (const std::size_t c : counts) EXPECT_GT(c, 1000u);
}

// zero_triples against its definition: exactly the triples of the set bits become +0.0, every
// other double (and the guard doubles around the 64 triples) keeps its bits; masks of none, all,
// single bits, the last chunk's first bits and random ones.
TEST(PairSplit, ZeroTriplesZeroesTheMarkedEntriesAndNothingElse) {
  std::mt19937_64 rng(29);
  std::vector<std::uint64_t> masks = {0,
                                      ~std::uint64_t{0},
                                      1,
                                      std::uint64_t{1} << 63,
                                      first_bits(5),
                                      first_bits(63),
                                      0x8000000000000001};
  for (int q = 0; q < 64; ++q) masks.push_back(std::uint64_t{1} << q);
  for (int r = 0; r < 200; ++r) masks.push_back(rng() & rng());
  constexpr std::size_t kGuard = 8;
  for (const std::uint64_t mask : masks) {
    std::vector<double> v(kGuard + 3 * 64 + kGuard);
    for (std::size_t d = 0; d < v.size(); ++d)
      v[d] = d == kGuard ? -0.0 : 1.0 + static_cast<double>(d);
    const std::vector<double> before = v;
    zero_triples(v.data() + kGuard, mask);
    for (std::size_t d = 0; d < v.size(); ++d) {
      const bool inside = d >= kGuard && d < kGuard + 3 * 64;
      const bool marked = inside && ((mask >> ((d - kGuard) / 3)) & 1) != 0;
      const double want = marked ? 0.0 : before[d];
      EXPECT_EQ(std::bit_cast<std::uint64_t>(v[d]), std::bit_cast<std::uint64_t>(want))
          << "mask " << std::hex << mask << std::dec << " double " << d;
    }
  }
}

}  // namespace
}  // namespace drumlab
