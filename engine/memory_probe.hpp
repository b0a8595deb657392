#pragma once
// How much heap the process holds, for measuring what the engine allocates (benchmarks, tests).
#include <malloc.h>

#include <cstddef>

namespace drumlab {

/// Bytes the allocator holds for live objects now (glibc mallinfo2: all arenas, mmap'd blocks
/// included); independent of what freed memory the process keeps. Not for the time step.
inline std::size_t heap_bytes_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

}  // namespace drumlab
