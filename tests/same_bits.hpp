#pragma once
// Bitwise equality for the tests' "bit-identical" checks (so -0.0 != 0.0 and NaN payloads count).
#include <cstring>
#include <vector>

namespace drumlab::test {

inline bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Same length and the same bytes (double, Vec3, ...: trivially copyable elements).
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace drumlab::test
