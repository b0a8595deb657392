#pragma once
// The half kick and the drift of four particles at a time (Simulation::kick, kick_drift). Four
// particles' 3-vectors are twelve consecutive doubles, three AVX registers; a per-particle scalar
// (1/m, h/I) is spread over them as s0 s0 s0 s1 | s1 s1 s2 s2 | s2 s3 s3 s3 and the update runs
// on the registers as they are, with no transposition. One particle at a time the two passes paid
// about 40 and 90 instructions a particle (callgrind, the demo drum), most of them loads of
// pointers and single lanes. The roundings are the one-particle loop's as GCC contracts it
// (v + h (f/m + g) as fma(h, fma(1/m, f, g), v), w + (h/I) t as fma(h/I, t, w), x + dt v as
// fma(dt, v, x)), so the lanes and a block's last particles (one at a time) give the same bits;
// the reference trajectories pin it.
#include <cstddef>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

namespace drumlab {

#if defined(__AVX2__) && defined(__FMA__)
/// A scalar per particle of four particles spread over their twelve components, or a constant
/// 3-vector repeated four times: the three registers' values.
struct Spread4 {
  __m256d a;
  __m256d b;
  __m256d c;
};

/// s[0..4) as s0 s0 s0 s1 | s1 s1 s2 s2 | s2 s3 s3 s3.
[[gnu::always_inline]] inline Spread4 spread_scalars(__m256d s) {
  return {_mm256_permute4x64_pd(s, _MM_SHUFFLE(1, 0, 0, 0)),
          _mm256_permute4x64_pd(s, _MM_SHUFFLE(2, 2, 1, 1)),
          _mm256_permute4x64_pd(s, _MM_SHUFFLE(3, 3, 3, 2))};
}

/// (x, y, z) as x y z x | y z x y | z x y z.
[[gnu::always_inline]] inline Spread4 repeat_vector(double x, double y, double z) {
  return {_mm256_setr_pd(x, y, z, x), _mm256_setr_pd(y, z, x, y), _mm256_setr_pd(z, x, y, z)};
}

/// v += h (inv_mass f + g) of four particles: v, f their twelve components, inv_mass four.
[[gnu::always_inline]] inline void kick_velocity4(double* v, const double* f,
                                                  const double* inv_mass, __m256d h,
                                                  const Spread4& g) {
  const Spread4 m = spread_scalars(_mm256_loadu_pd(inv_mass));
  const __m256d m3[3] = {m.a, m.b, m.c};
  const __m256d g3[3] = {g.a, g.b, g.c};
  for (int r = 0; r < 3; ++r) {
    const __m256d a = _mm256_fmadd_pd(m3[r], _mm256_loadu_pd(f + 4 * r), g3[r]);
    _mm256_storeu_pd(v + 4 * r, _mm256_fmadd_pd(h, a, _mm256_loadu_pd(v + 4 * r)));
  }
}

/// w += (h inv_inertia) t of four particles.
[[gnu::always_inline]] inline void kick_spin4(double* w, const double* t, const double* inv_inertia,
                                              __m256d h) {
  const Spread4 s = spread_scalars(_mm256_mul_pd(h, _mm256_loadu_pd(inv_inertia)));
  const __m256d s3[3] = {s.a, s.b, s.c};
  for (int r = 0; r < 3; ++r) {
    _mm256_storeu_pd(
        w + 4 * r, _mm256_fmadd_pd(s3[r], _mm256_loadu_pd(t + 4 * r), _mm256_loadu_pd(w + 4 * r)));
  }
}

/// x += dt v of four particles; returns max(|component|) of the new x over the twelve, folded
/// into `abs_max` (a running maximum, lane by lane).
[[gnu::always_inline]] inline __m256d drift4(double* x, const double* v, __m256d dt,
                                             __m256d abs_max) {
  const __m256d sign = _mm256_set1_pd(-0.0);
  for (int r = 0; r < 3; ++r) {
    const __m256d y = _mm256_fmadd_pd(dt, _mm256_loadu_pd(v + 4 * r), _mm256_loadu_pd(x + 4 * r));
    _mm256_storeu_pd(x + 4 * r, y);
    abs_max = _mm256_max_pd(_mm256_andnot_pd(sign, y), abs_max);  // a NaN is left out
  }
  return abs_max;
}

/// Zeroes twelve doubles.
[[gnu::always_inline]] inline void zero12(double* a) {
  const __m256d z = _mm256_setzero_pd();
  _mm256_storeu_pd(a, z);
  _mm256_storeu_pd(a + 4, z);
  _mm256_storeu_pd(a + 8, z);
}

/// The largest lane of v.
[[gnu::always_inline]] inline double max_lane(__m256d v) {
  const __m128d m = _mm_max_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_max_sd(m, _mm_unpackhi_pd(m, m)));
}
#endif

}  // namespace drumlab
