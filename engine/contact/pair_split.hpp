#pragma once
// The contact pair loop's split of a chunk of listed pairs (contact_model.cpp, split_entries):
// which of at most 64 entries overlap, how many touch, and, in a scene with cohesive parts, each
// entry's touch mark (touch_sift.hpp). The loop gathers each entry's squared centre distance and
// radii's sum into two arrays; the tests then run on 8 (AVX-512) or 4 (AVX2) entries at once,
// where per entry they cost the loop a dozen scalar instructions and a chain through its
// partition counters. The same tests, rounded the same way, as the scalar loop's.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "engine/contact/touch_sift.hpp"

#if defined(__AVX2__) && defined(__BMI2__)
#include <immintrin.h>
#endif

namespace drumlab {

/// The split of n <= 64 entries: bit q of `overlapping` set where entry q overlaps (0 < |d|^2 <
/// (r_i + r_j)^2), `touching` the entries with |d|^2 <= (r_i + r_j + tolerance)^2.
struct PairSplit {
  std::uint64_t overlapping = 0;
  std::size_t touching = 0;
};

/// One entry's tests, the definitions the SIMD paths reproduce (overlapping: touch_mark's).
[[gnu::always_inline]] inline bool split_overlaps(double dist2, double sum_r) {
  return (touch_mark(dist2, sum_r) & kOverlapping) != 0;
}
[[gnu::always_inline]] inline bool split_touches(double dist2, double sum_r, double tolerance) {
  const double cut = sum_r + tolerance;
  return dist2 <= cut * cut;
}

/// The split of entries q < n <= 64 from their squared distances dist2[q] and radii's sums
/// sum_r[q]; kMark: also mark[q] = touch_mark(dist2[q], sum_r[q]).
template <bool kMark>
[[gnu::always_inline]] inline PairSplit split_pairs(const double* dist2, const double* sum_r,
                                                    std::size_t n, double tolerance,
                                                    std::uint8_t* mark) {
  PairSplit s;
  std::size_t q = 0;
#if defined(__AVX512F__) && defined(__BMI2__)
  constexpr std::uint64_t kBytes = 0x0101010101010101ULL;  // bit b of a flag's mask to byte b
  const __m512d tol = _mm512_set1_pd(tolerance);
  for (; q + 8 <= n; q += 8) {
    const __m512d d = _mm512_loadu_pd(dist2 + q);
    const __m512d r = _mm512_loadu_pd(sum_r + q);
    const __m512d r2 = _mm512_mul_pd(r, r);
    const __m512d cut = _mm512_add_pd(r, tol);
    const unsigned apart = _mm512_cmp_pd_mask(d, _mm512_setzero_pd(), _CMP_NEQ_UQ);  // d != 0
    const unsigned overlapping = _mm512_cmp_pd_mask(d, r2, _CMP_LT_OQ) & apart;
    s.overlapping |= static_cast<std::uint64_t>(overlapping) << q;
    s.touching += static_cast<std::size_t>(std::popcount(
        static_cast<unsigned>(_mm512_cmp_pd_mask(d, _mm512_mul_pd(cut, cut), _CMP_LE_OQ))));
    if constexpr (kMark) {
      const unsigned touch = _mm512_cmp_pd_mask(d, r2, _CMP_NGT_UQ);  // !(d > r2)
      const std::uint64_t bytes = _pdep_u64(touch, kBytes * kTouchOrEqual) |
                                  _pdep_u64(apart, kBytes * kApartCentres) |
                                  _pdep_u64(overlapping, kBytes * kOverlapping);
      std::memcpy(mark + q, &bytes, 8);
    }
  }
#elif defined(__AVX2__) && defined(__BMI2__)
  constexpr std::uint32_t kBytes = 0x01010101U;
  const __m256d tol = _mm256_set1_pd(tolerance);
  const auto bits = [](__m256d c) { return static_cast<unsigned>(_mm256_movemask_pd(c)); };
  for (; q + 4 <= n; q += 4) {
    const __m256d d = _mm256_loadu_pd(dist2 + q);
    const __m256d r = _mm256_loadu_pd(sum_r + q);
    const __m256d r2 = _mm256_mul_pd(r, r);
    const __m256d cut = _mm256_add_pd(r, tol);
    const unsigned apart = bits(_mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_NEQ_UQ));
    const unsigned overlapping = bits(_mm256_cmp_pd(d, r2, _CMP_LT_OQ)) & apart;
    s.overlapping |= static_cast<std::uint64_t>(overlapping) << q;
    s.touching += static_cast<std::size_t>(
        std::popcount(bits(_mm256_cmp_pd(d, _mm256_mul_pd(cut, cut), _CMP_LE_OQ))));
    if constexpr (kMark) {
      const unsigned touch = bits(_mm256_cmp_pd(d, r2, _CMP_NGT_UQ));
      const std::uint32_t bytes = _pdep_u32(touch, kBytes * kTouchOrEqual) |
                                  _pdep_u32(apart, kBytes * kApartCentres) |
                                  _pdep_u32(overlapping, kBytes * kOverlapping);
      std::memcpy(mark + q, &bytes, 4);
    }
  }
#endif
  for (; q < n; ++q) {
    s.overlapping |= static_cast<std::uint64_t>(split_overlaps(dist2[q], sum_r[q])) << q;
    s.touching += static_cast<std::size_t>(split_touches(dist2[q], sum_r[q], tolerance));
    if constexpr (kMark) mark[q] = touch_mark(dist2[q], sum_r[q]);
  }
  return s;
}

/// The entries q < n as bits (n <= 64).
inline std::uint64_t first_bits(std::size_t n) {
  return n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
}

/// Zeroes the triples v[3q], v[3q + 1], v[3q + 2] for each set bit q of `mask` (a chunk's entries
/// that do not overlap: their tangential histories, three doubles an entry), and writes nothing
/// else. With AVX-512, eight entries (24 doubles) take three masked stores, each bit of the
/// entries' byte spread to three doubles by one pdep; else one entry at a time.
inline void zero_triples(double* v, std::uint64_t mask) {
#if defined(__AVX512F__) && defined(__BMI2__)
  constexpr std::uint32_t kEveryThird = 0x249249;  // bits 0, 3, ..., 21
  const __m512d zero = _mm512_setzero_pd();
  for (std::size_t g = 0; g < 8 && mask != 0; ++g, mask >>= 8, v += 24) {
    // Bit q of the byte at bits 3q..3q+2: disjoint triples, so the product carries nothing.
    const std::uint32_t spread =
        _pdep_u32(static_cast<std::uint32_t>(mask & 0xff), kEveryThird) * 7;
    _mm512_mask_storeu_pd(v, static_cast<__mmask8>(spread), zero);
    _mm512_mask_storeu_pd(v + 8, static_cast<__mmask8>(spread >> 8), zero);
    _mm512_mask_storeu_pd(v + 16, static_cast<__mmask8>(spread >> 16), zero);
  }
#else
  for_each_bit(mask, [&](std::size_t q) {
    v[3 * q] = 0.0;
    v[3 * q + 1] = 0.0;
    v[3 * q + 2] = 0.0;
  });
#endif
}

}  // namespace drumlab
