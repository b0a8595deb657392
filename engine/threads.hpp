#pragma once
// OpenMP thread count and number, also when built without OpenMP.
#ifdef _OPENMP
#include <omp.h>
#endif

namespace drumlab {

/// Threads a parallel region started now would get (1 without OpenMP).
inline int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/// This thread's number in the current parallel region (0 outside one or without OpenMP).
inline int thread_number() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// Sets the thread count of later parallel regions (no effect without OpenMP).
inline void set_thread_count([[maybe_unused]] int threads) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#endif
}

}  // namespace drumlab
