#pragma once
// The touch marks the contact pair loop writes for every listed pair of a scene with cohesive
// parts, and the cohesive pass's sift of them (cohesion_loops.cpp): which listed pairs of a chunk
// of at most 64 a cohesive part may act on, as a 64-bit mask (bit q: entry k0 + q), from the marks
// and the parts' live flags. Per entry the scalar sift paid about a dozen instructions and a store
// (most entries are apart with no live state: nothing to do); with SIMD the masks of 64 entries
// take a few dozen instructions. The same entries in the same order.

#include <bit>
#include <cstddef>
#include <cstdint>

#if defined(__AVX2__) && defined(__BMI2__)
#include <immintrin.h>
#endif

namespace drumlab {

/// A listed pair's touch mark at squared centre distance dist2, radii summing to sum_r:
/// kTouchOrEqual if |d| <= r_i + r_j (a part may act without live state), kApartCentres if
/// the centres differ (|d| > 0: the pair has a direction).
/// kOverlapping if the pair overlaps, |d| < r_i + r_j with |d| > 0 (the pair loop's contact: a
/// TouchingPull, cohesion_loops.hpp, has added its bridge's pull).
inline constexpr std::uint8_t kTouchOrEqual = 1;
inline constexpr std::uint8_t kApartCentres = 2;
inline constexpr std::uint8_t kOverlapping = 4;
[[gnu::always_inline]] inline std::uint8_t touch_mark(double dist2, double sum_r) {
  const auto touch = static_cast<unsigned>(!(dist2 > sum_r * sum_r));
  const auto apart = static_cast<unsigned>(dist2 != 0.0);
  const auto overlapping = static_cast<unsigned>(dist2 < sum_r * sum_r) & apart;
  return static_cast<std::uint8_t>(touch * kTouchOrEqual | apart * kApartCentres |
                                   overlapping * kOverlapping);
}
inline constexpr std::size_t kSiftChunk = 64;

/// Bit q set where mark[q] has the bit `flag` (one of touch_mark's flags), for q < n <= 64.
inline std::uint64_t mark_mask_scalar(const std::uint8_t* mark, std::size_t n, std::uint8_t flag) {
  std::uint64_t m = 0;
  for (std::size_t q = 0; q < n; ++q) m |= static_cast<std::uint64_t>((mark[q] & flag) != 0) << q;
  return m;
}

/// The three flags' masks of mark[0, n).
struct MarkMasks {
  std::uint64_t touch = 0;
  std::uint64_t apart = 0;
  std::uint64_t overlapping = 0;
};

/// mark_mask_scalar of touch_mark's three flags.
inline MarkMasks mark_masks(const std::uint8_t* mark, std::size_t n) {
#if defined(__AVX512BW__)
  if (n == kSiftChunk) {
    const __m512i v = _mm512_loadu_si512(mark);
    const auto bits = [&](std::uint8_t flag) {
      return _mm512_test_epi8_mask(v, _mm512_set1_epi8(static_cast<char>(flag)));
    };
    return {bits(kTouchOrEqual), bits(kApartCentres), bits(kOverlapping)};
  }
#elif defined(__AVX2__) && defined(__BMI2__)
  if (n == kSiftChunk) {
    const __m256i lo = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(mark));
    const __m256i hi = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(mark + 32));
    // The flag's bit of every byte moved to the byte's sign bit (a 16-bit shift keeps each byte's
    // own bit there), then one bit a byte.
    const auto bits = [&](std::uint8_t flag) {
      const __m128i s = _mm_cvtsi32_si128(7 - std::countr_zero(flag));
      const auto l = static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_sll_epi16(lo, s)));
      const auto h = static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_sll_epi16(hi, s)));
      return static_cast<std::uint64_t>(l) | (static_cast<std::uint64_t>(h) << 32);
    };
    return {bits(kTouchOrEqual), bits(kApartCentres), bits(kOverlapping)};
  }
#endif
  return {mark_mask_scalar(mark, n, kTouchOrEqual), mark_mask_scalar(mark, n, kApartCentres),
          mark_mask_scalar(mark, n, kOverlapping)};
}

/// Bit q set where s[2 q] > 0 (false for NaN), q < n <= 64: the live flags of a plain liquid
/// bridge's state (LiquidBridge::live, state size 2, the only part) of n consecutive entries.
inline std::uint64_t positive_even_mask(const double* s, std::size_t n) {
#if defined(__AVX512F__) && defined(__BMI2__)
  if (n == kSiftChunk) {
    std::uint64_t m = 0;
    const __m512d zero = _mm512_setzero_pd();
    for (std::size_t g = 0; g < kSiftChunk / 8; ++g) {
      const unsigned a = _mm512_cmp_pd_mask(_mm512_loadu_pd(s + 16 * g), zero, _CMP_GT_OQ);
      const unsigned b = _mm512_cmp_pd_mask(_mm512_loadu_pd(s + 16 * g + 8), zero, _CMP_GT_OQ);
      m |= static_cast<std::uint64_t>(_pext_u32(a | (b << 8), 0x5555u)) << (8 * g);
    }
    return m;
  }
#elif defined(__AVX2__) && defined(__BMI2__)
  if (n == kSiftChunk) {
    std::uint64_t m = 0;
    const __m256d zero = _mm256_setzero_pd();
    for (std::size_t g = 0; g < kSiftChunk / 4; ++g) {
      const auto a = static_cast<unsigned>(
          _mm256_movemask_pd(_mm256_cmp_pd(_mm256_loadu_pd(s + 8 * g), zero, _CMP_GT_OQ)));
      const auto b = static_cast<unsigned>(
          _mm256_movemask_pd(_mm256_cmp_pd(_mm256_loadu_pd(s + 8 * g + 4), zero, _CMP_GT_OQ)));
      m |= static_cast<std::uint64_t>(_pext_u32(a | (b << 4), 0x55u)) << (4 * g);
    }
    return m;
  }
#endif
  std::uint64_t m = 0;
  for (std::size_t q = 0; q < n; ++q) m |= static_cast<std::uint64_t>(s[2 * q] > 0.0) << q;
  return m;
}

/// The entries a cohesive part may act on: distinct centres, and touching (a part may act without
/// live state: a bridge forms on contact, sjkr acts while overlapping) or live.
inline std::uint64_t take_mask(const MarkMasks& m, std::uint64_t live) {
  return (m.touch | live) & m.apart;
}
/// take_mask without the overlapping pairs whose state is live (the contact pair loop has added
/// their pull, TouchingPull): touching without live state (a bridge may form), or live and not
/// overlapping (apart, or touching with |d| = r_i + r_j exactly); distinct centres.
inline std::uint64_t take_not_pulled_mask(const MarkMasks& m, std::uint64_t live) {
  return ((m.touch & ~live) | (live & ~m.overlapping)) & m.apart;
}

/// visit(q) for every set bit q of `mask`, by increasing q.
template <class Visit>
[[gnu::always_inline]] inline void for_each_bit(std::uint64_t mask, Visit&& visit) {
  for (; mask != 0; mask &= mask - 1) visit(static_cast<std::size_t>(std::countr_zero(mask)));
}

}  // namespace drumlab
