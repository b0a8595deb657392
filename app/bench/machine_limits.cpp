#include "app/bench/machine_limits.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <new>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace drumlab::bench {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Best rate of `body(reps)` (which does `work_per_rep` units per repetition) over `trials`, each
/// run long enough to last about `seconds`.
template <class Body>
double best_rate(Body&& body, double work_per_rep, double seconds, int trials) {
  std::uint64_t reps = 1;
  for (;;) {  // calibrate: double the repetitions until one run takes a tenth of the target
    const auto t0 = Clock::now();
    body(reps);
    if (seconds_since(t0) > 0.1 * seconds || reps > (1ULL << 40)) break;
    reps *= 2;
  }
  reps *= 10;
  double best = 0.0;
  for (int t = 0; t < trials; ++t) {
    const auto t0 = Clock::now();
    body(reps);
    const double s = seconds_since(t0);
    if (s > 0.0) best = std::max(best, work_per_rep * static_cast<double>(reps) / s);
  }
  return best;
}

volatile double g_sink = 0.0;  // keeps the kernels' results alive

#if defined(__AVX2__) && defined(__FMA__)
[[maybe_unused]] constexpr const char* kIsa = "AVX2 + FMA (256-bit)";
// 12 chains: enough to cover 2 FMA units of 4-cycle latency, and with the two constants 14 of the
// 16 ymm registers (more chains would spill to memory and measure the spills).
constexpr int kFmaChains = 12;
/// 12 independent chains of 256-bit FMAs per iteration: 12 x 4 lanes x 2 flops.
[[maybe_unused]] void fma_kernel(std::uint64_t reps) {
  __m256d acc[kFmaChains];
  for (int c = 0; c < kFmaChains; ++c) acc[c] = _mm256_set1_pd(1.0 + 1e-3 * c);
  const __m256d a = _mm256_set1_pd(0.999999);
  const __m256d b = _mm256_set1_pd(1e-7);
  for (std::uint64_t r = 0; r < reps; ++r) {
    for (int c = 0; c < kFmaChains; ++c) acc[c] = _mm256_fmadd_pd(acc[c], a, b);
  }
  __m256d s = acc[0];
  for (int c = 1; c < kFmaChains; ++c) s = _mm256_add_pd(s, acc[c]);
  g_sink = _mm256_cvtsd_f64(s);
}
[[maybe_unused]] constexpr double kFlopsPerFmaRep = kFmaChains * 4 * 2;

/// 8 independent chains, each a square root and a division per iteration (4 lanes each).
void divsqrt_kernel(std::uint64_t reps) {
  __m256d x[8];
  for (int c = 0; c < 8; ++c) x[c] = _mm256_set1_pd(2.0 + c);
  const __m256d k = _mm256_set1_pd(3.0);
  for (std::uint64_t r = 0; r < reps; ++r) {
    for (int c = 0; c < 8; ++c) x[c] = _mm256_div_pd(k, _mm256_sqrt_pd(x[c]));
  }
  __m256d s = x[0];
  for (int c = 1; c < 8; ++c) s = _mm256_add_pd(s, x[c]);
  g_sink = _mm256_cvtsd_f64(s);
}
constexpr double kDivSqrtPerRep = 8 * 4 * 2;
#else
[[maybe_unused]] constexpr const char* kIsa = "scalar/SSE2 (build without AVX2)";
[[maybe_unused]] void fma_kernel(std::uint64_t reps) {
  double acc[16];
  for (int c = 0; c < 16; ++c) acc[c] = 1.0 + 1e-3 * c;
  for (std::uint64_t r = 0; r < reps; ++r) {
    for (double& v : acc) v = v * 0.999999 + 1e-7;
  }
  double s = 0.0;
  for (double v : acc) s += v;
  g_sink = s;
}
[[maybe_unused]] constexpr double kFlopsPerFmaRep = 16 * 2;
void divsqrt_kernel(std::uint64_t reps) {
  double x[8];
  for (int c = 0; c < 8; ++c) x[c] = 2.0 + c;
  for (std::uint64_t r = 0; r < reps; ++r) {
    for (double& v : x) v = 3.0 / std::sqrt(v);
  }
  double s = 0.0;
  for (double v : x) s += v;
  g_sink = s;
}
constexpr double kDivSqrtPerRep = 8 * 2;
#endif

#if defined(__x86_64__)
/// The same as fma_kernel with 512-bit registers (only called when the CPU has AVX-512F).
[[gnu::target("avx512f")]] void fma512_kernel(std::uint64_t reps) {
  __m512d acc[16];
  for (int c = 0; c < 16; ++c) acc[c] = _mm512_set1_pd(1.0 + 1e-3 * c);
  const __m512d a = _mm512_set1_pd(0.999999);
  const __m512d b = _mm512_set1_pd(1e-7);
  for (std::uint64_t r = 0; r < reps; ++r) {
    for (int c = 0; c < 16; ++c) acc[c] = _mm512_fmadd_pd(acc[c], a, b);
  }
  __m512d s = acc[0];
  for (int c = 1; c < 16; ++c) s = _mm512_add_pd(s, acc[c]);
  alignas(64) double lanes[8];
  _mm512_store_pd(lanes, s);
  g_sink = lanes[0] + lanes[7];
}
/// 16 independent chains of 512-bit FMAs per iteration: 16 x 8 lanes x 2 flops.
constexpr double kFlopsPerFma512Rep = 16 * 8 * 2;
#endif

/// STREAM triad over three arrays of `n` doubles (reps passes).
struct Triad {
  std::size_t n;
  std::unique_ptr<double[]> a, b, c;
  explicit Triad(std::size_t count)
      : n(count), a(new double[count]), b(new double[count]), c(new double[count]) {
    for (std::size_t i = 0; i < n; ++i) {
      a[i] = 0.0;
      b[i] = 1.0;
      c[i] = 2.0;
    }
  }
  void operator()(std::uint64_t reps) {
    double* __restrict pa = a.get();
    const double* __restrict pb = b.get();
    const double* __restrict pc = c.get();
    for (std::uint64_t r = 0; r < reps; ++r) {
      const double s = 1.0 + 1e-9 * static_cast<double>(r & 7U);
      for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    }
    g_sink = pa[n / 2];
  }
};

std::size_t cache_bytes(int name, std::size_t fallback) {
  const long v = sysconf(name);
  return v > 0 ? static_cast<std::size_t>(v) : fallback;
}

}  // namespace

const BandwidthLevel& MachineLimits::level_for(double working_set) const {
  for (const BandwidthLevel& l : levels) {
    if (working_set <= 2.0 * static_cast<double>(l.bytes) && l.name != "memory") return l;
  }
  return levels.back();
}

MachineLimits measure_machine_limits(bool quick) {
  const double seconds = quick ? 0.02 : 0.2;
  const int trials = quick ? 2 : 5;
  MachineLimits m;
  m.divsqrt_per_s = best_rate(divsqrt_kernel, kDivSqrtPerRep, seconds, trials);
#if defined(__AVX512F__)
  // An AVX-512 build (-march=x86-64-v4): its own peak is the 512-bit one.
  m.isa = "AVX-512 + FMA (512-bit)";
  m.peak_gflops = best_rate(fma512_kernel, kFlopsPerFma512Rep, seconds, trials) * 1e-9;
#else
  m.isa = kIsa;
  m.peak_gflops = best_rate(fma_kernel, kFlopsPerFmaRep, seconds, trials) * 1e-9;
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx512f")) {
    m.peak_gflops_512 = best_rate(fma512_kernel, kFlopsPerFma512Rep, seconds, trials) * 1e-9;
  }
#endif
#endif
  // Working sets at half of each cache (the triad's three arrays), so that they stay in it; the
  // last level at 16 MiB at most, because a core reaches only its own part of a large shared L3.
  const std::size_t l1 = cache_bytes(_SC_LEVEL1_DCACHE_SIZE, 32 << 10) / 2;
  const std::size_t l2 = cache_bytes(_SC_LEVEL2_CACHE_SIZE, 512 << 10) / 2;
  const std::size_t l3 =
      std::min<std::size_t>(cache_bytes(_SC_LEVEL3_CACHE_SIZE, 16 << 20) / 2, 16 << 20);
  const std::size_t mem = quick ? (64U << 20) : (768U << 20);
  const std::pair<const char*, std::size_t> sizes[] = {
      {"L1", l1}, {"L2", l2}, {"L3", l3}, {"memory", mem}};
  for (const auto& [name, bytes] : sizes) {
    Triad triad(bytes / 24);
    const double gbs = best_rate(triad, 24.0 * static_cast<double>(triad.n), seconds, trials);
    m.levels.push_back({name, bytes, gbs * 1e-9});
  }
  return m;
}

}  // namespace drumlab::bench
