#pragma once
// Loads of four particles' state into four SIMD lanes, for the contact batches
// (contact_kernel.hpp, PairBatch::gather). A batch's lanes were filled one contact at a time,
// a scalar load and a scalar store a component (with the kernel's vector loads of them after):
// about 85 instructions a contact, more than the kernel's arithmetic (callgrind, the demo drum).
// Here four contacts' 3-vectors are loaded as pairs {x, y} and single z's and transposed in
// registers (no gather instructions: on the AMD cores measured, four scalar loads beat them),
// then stored as whole vectors. The values are the same; only how they travel changes.
#include <cstddef>

#include "engine/types.hpp"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace drumlab {

#if defined(__AVX2__)
/// The components of a[o[0]], ..., a[o[3]] (3-vectors of doubles, a[o] at a + o, o the element's
/// offset in doubles) as x, y, z vectors, lane q from a[o[q]].
struct Lanes4x3 {
  __m256d x;
  __m256d y;
  __m256d z;
};
[[gnu::always_inline]] inline Lanes4x3 load_lanes3(const double* a, const std::size_t o[4]) {
  const double* a0 = a + o[0];
  const double* a1 = a + o[1];
  const double* a2 = a + o[2];
  const double* a3 = a + o[3];
  const __m256d xy02 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(a0)),
                                            _mm_loadu_pd(a2), 1);  // x0 y0 x2 y2
  const __m256d xy13 = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(a1)),
                                            _mm_loadu_pd(a3), 1);  // x1 y1 x3 y3
  const __m128d z01 = _mm_loadh_pd(_mm_load_sd(a0 + 2), a1 + 2);
  const __m128d z23 = _mm_loadh_pd(_mm_load_sd(a2 + 2), a3 + 2);
  return {_mm256_unpacklo_pd(xy02, xy13), _mm256_unpackhi_pd(xy02, xy13),
          _mm256_insertf128_pd(_mm256_castpd128_pd256(z01), z23, 1)};
}

/// a[n[0]], ..., a[n[3]] as one vector.
[[gnu::always_inline]] inline __m256d load_lanes1(const double* a, const std::size_t n[4]) {
  const __m128d v01 = _mm_loadh_pd(_mm_load_sd(a + n[0]), a + n[1]);
  const __m128d v23 = _mm_loadh_pd(_mm_load_sd(a + n[2]), a + n[3]);
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(v01), v23, 1);
}

/// Stores the lanes of v to x[0..4), y, z (each 32-byte aligned).
[[gnu::always_inline]] inline void store_lanes3(const Lanes4x3& v, double* x, double* y,
                                                double* z) {
  _mm256_store_pd(x, v.x);
  _mm256_store_pd(y, v.y);
  _mm256_store_pd(z, v.z);
}

[[gnu::always_inline]] inline Lanes4x3 operator-(const Lanes4x3& a, const Lanes4x3& b) {
  return {_mm256_sub_pd(a.x, b.x), _mm256_sub_pd(a.y, b.y), _mm256_sub_pd(a.z, b.z)};
}

/// nearest_image_z (periodic.hpp) of four lanes, for a period > 0: the same comparisons and the
/// same one shift, by selects.
[[gnu::always_inline]] inline __m256d nearest_image_z4(__m256d dz, double period) {
  const __m256d p = _mm256_set1_pd(period);
  const __m256d half = _mm256_set1_pd(0.5 * period);
  const __m256d minus_half = _mm256_set1_pd(-0.5 * period);
  const __m256d above = _mm256_cmp_pd(dz, half, _CMP_GT_OQ);
  const __m256d below = _mm256_cmp_pd(dz, minus_half, _CMP_LT_OQ);
  const __m256d shifted = _mm256_blendv_pd(dz, _mm256_add_pd(dz, p), below);
  return _mm256_blendv_pd(shifted, _mm256_sub_pd(dz, p), above);
}
#endif

}  // namespace drumlab
