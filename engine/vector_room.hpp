#pragma once
// Growth of the per-pair arrays. std::vector grows past its capacity to twice its size, so a list
// that grows a little at a time (a Verlet list patched until it has grown by a quarter, the contact
// list and the force loop's buffers over it) came to hold twice the memory it needs. These reserve
// a quarter more instead: one allocation covers the patches between two rebuilds.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace drumlab {

/// v.resize(n), reserving n + n/4 (at least 64 elements) first when n is past v's capacity.
template <class T>
void resize_with_room(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(std::max<std::size_t>(n + n / 4, 64));
  v.resize(n);
}

}  // namespace drumlab
