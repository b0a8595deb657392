#pragma once
// How much heap the process holds, for measuring what the engine allocates (benchmarks, tests).
#include <malloc.h>

#include <cstddef>

// Under AddressSanitizer or ThreadSanitizer malloc is the sanitizer's, which glibc's mallinfo2
// does not see: ask the sanitizer's allocator instead.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define DRUMLAB_SANITIZER_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define DRUMLAB_SANITIZER_ALLOCATOR 1
#endif
#endif
#ifdef DRUMLAB_SANITIZER_ALLOCATOR
// The sanitizers' allocator interface (sanitizer/allocator_interface.h, not installed with
// Debian's GCC 12).
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace drumlab {

/// Bytes the allocator holds for live objects now (glibc mallinfo2: all arenas, mmap'd blocks
/// included; under a sanitizer, the bytes its allocator has handed out); independent of what
/// freed memory the process keeps. Not for the time step.
inline std::size_t heap_bytes_in_use() {
#ifdef DRUMLAB_SANITIZER_ALLOCATOR
  return __sanitizer_get_current_allocated_bytes();
#else
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
#endif
}

}  // namespace drumlab
