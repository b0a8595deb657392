#pragma once
// What one core of this machine can do, measured: the roofs of `drumlab bench roofline`.
//
// * Peak double-precision flops: independent fused multiply-adds on full vector registers (as
//   many chains as fit the register file, enough to cover the FMA latency), with the
//   instruction set the build uses (AVX-512 for -march=x86-64-v4, AVX2 + FMA for x86-64-v3) and,
//   in a build without AVX-512 on a CPU that has it, AVX-512 for reference.
// * Divisions and square roots: the DEM kernels are full of them (unit normals, Hertz
//   stiffness, the Coulomb limit), and they run on a separate, slower unit; a second compute roof.
// * Bandwidth of one core from each level of the memory hierarchy: the STREAM triad
//   a[i] = b[i] + s c[i] on arrays whose total size fits L1, L2, L3 or only memory (24 bytes
//   counted per element, as STREAM does: the write-allocate read is not counted).
// Each figure is the best of a few timed repetitions (a shared machine only slows a run down).
#include <cstddef>
#include <string>
#include <vector>

namespace drumlab::bench {

struct BandwidthLevel {
  std::string name;       ///< "L1", "L2", "L3", "memory"
  std::size_t bytes = 0;  ///< total size of the triad's three arrays
  double gbs = 0.0;       ///< GB/s (1e9 bytes), triad
};

struct MachineLimits {
  std::string isa;               ///< instruction set of the peak (the build's)
  double peak_gflops = 0.0;      ///< double precision, one core, the build's ISA
  double peak_gflops_512 = 0.0;  ///< AVX-512, when the CPU has it and the build does not
  double divsqrt_per_s = 0.0;    ///< double-precision divisions and square roots (results / s)
  std::vector<BandwidthLevel> levels;  ///< from the smallest working set to the largest

  /// Bandwidth of the smallest level whose size holds `working_set` bytes (memory if none).
  const BandwidthLevel& level_for(double working_set) const;
};

/// Measures the limits (about 3 s; `quick`: about 0.3 s, coarser figures, for tests).
MachineLimits measure_machine_limits(bool quick);

}  // namespace drumlab::bench
