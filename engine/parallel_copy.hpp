#pragma once
// Element-wise copies, fills and comparisons of per-particle arrays on every thread: the Verlet
// list's rebuild and its per-step check otherwise ran them on one thread while the others waited.
// Each element is copied or compared on its own, so the results do not depend on the team.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace drumlab {

/// Below this many elements one thread does it: starting the team would cost more.
inline constexpr std::int64_t kParallelMinElements = 4096;

/// to = from, element by element.
template <class T>
void parallel_assign(std::vector<T>& to, std::span<const T> from) {
  to.resize(from.size());
  const auto n = static_cast<std::int64_t>(from.size());
  T* out = to.data();
  const T* in = from.data();
#pragma omp parallel for schedule(static) if (n >= kParallelMinElements)
  for (std::int64_t i = 0; i < n; ++i) out[i] = in[i];
}

/// to = n copies of value.
template <class T>
void parallel_fill(std::vector<T>& to, std::size_t n, const T& value) {
  to.resize(n);
  const auto count = static_cast<std::int64_t>(n);
  T* out = to.data();
#pragma omp parallel for schedule(static) if (count >= kParallelMinElements)
  for (std::int64_t i = 0; i < count; ++i) out[i] = value;
}

/// The same sizes and every element equal (==).
template <class T>
bool parallel_equal(std::span<const T> a, std::span<const T> b) {
  if (a.size() != b.size()) return false;
  const auto n = static_cast<std::int64_t>(a.size());
  int differ = 0;
#pragma omp parallel for schedule(static) reduction(| : differ) if (n >= kParallelMinElements)
  for (std::int64_t i = 0; i < n; ++i) differ |= !(a[i] == b[i]);
  return differ == 0;
}

}  // namespace drumlab
