#pragma once
// Checks shared by every search method, the periodic minimum-image distance, and the per-thread
// output slices of the parallel searches.
#include <chrono>
#include <cmath>
#include <vector>

#include "engine/periodic.hpp"
#include "engine/search/contact_search.hpp"

namespace drumlab {

/// Throws InputError if the input is inconsistent (size mismatch, non-finite or non-positive
/// radius, non-finite position, negative margin, position outside the domain or period).
void validate_search_input(const SearchInput& in);

/// Sorts pairs by (i, j) in O(pairs + n): counting sort by i, insertion sort of the short rows.
/// `scratch` is reused between calls.
void sort_pairs(std::vector<IndexPair>& pairs, std::size_t n, std::vector<IndexPair>& scratch,
                std::vector<std::uint32_t>& counts);

using SearchClock = std::chrono::steady_clock;

/// Seconds from `since` to now.
/// Per-thread output of a parallel pair search. Each thread appends to its own slice; with each
/// thread taking a contiguous block of the work in order (OpenMP static schedule, or an explicit
/// split), join() gives the same sequence for any thread count.
class PairSlices {
 public:
  /// One empty slice per thread of the next parallel region; returns the thread count.
  int prepare(int threads) {
    slices_.resize(static_cast<std::size_t>(threads));
    for (auto& s : slices_) s.clear();
    return threads;
  }
  /// The slice of thread t.
  std::vector<IndexPair>& slice(int t) { return slices_[static_cast<std::size_t>(t)]; }
  /// Appends the slices to `out` in thread order.
  void join(std::vector<IndexPair>& out) const {
    for (const auto& s : slices_) out.insert(out.end(), s.begin(), s.end());
  }

 private:
  std::vector<std::vector<IndexPair>> slices_;
};

inline double seconds_since(SearchClock::time_point since) {
  return std::chrono::duration<double>(SearchClock::now() - since).count();
}

/// Squared distance between a and b, using the minimum image along z when period > 0.
inline double distance_squared(const Vec3& a, const Vec3& b, double period) {
  const double dx = a.x() - b.x();
  const double dy = a.y() - b.y();
  const double dz = nearest_image_z(a.z() - b.z(), period);
  return dx * dx + dy * dy + dz * dz;
}

/// A grid's particles in cell-sorted order: slot t holds original particle order[t].
struct SortedParticles {
  const Vec3* position;
  const double* radius;
  const Index* order;
};

/// The hot loop of every grid search: tests particle pi (at xi, radius ri) against the slots
/// [begin, end) of `s` and appends each pair within ri + r_t + margin as (min, max) of the
/// original indices. Returns the tests made. Every pointer and coordinate is read once before the
/// loop (through references the compiler would re-read them after each append), and the periodic
/// image is a separate loop.
[[gnu::always_inline]] inline std::uint32_t scan_slots(const SortedParticles& s, const Vec3& xi,
                                                       double ri, Index pi, std::uint32_t begin,
                                                       std::uint32_t end, double margin,
                                                       double period, std::vector<IndexPair>& out) {
  const Vec3 x = xi;
  const Vec3* const position = s.position;
  const double* const radius = s.radius;
  const Index* const order = s.order;
  const auto scan = [&](auto distance2) {
    for (std::uint32_t t = begin; t < end; ++t) {
      const double cut = ri + radius[t] + margin;
      if (distance2(position[t]) <= cut * cut) {
        const Index pj = order[t];
        out.push_back(pi < pj ? IndexPair{pi, pj} : IndexPair{pj, pi});
      }
    }
  };
  if (period > 0.0) {
    scan([&](const Vec3& y) { return distance_squared(x, y, period); });
  } else {
    scan([&](const Vec3& y) { return distance_squared(x, y, 0.0); });
  }
  return end > begin ? end - begin : 0;
}

/// Cut-off distance for a pair: r_i + r_j + margin + the touching tolerance.
inline double pair_cutoff(double ri, double rj, double margin) {
  return ri + rj + margin + kTouchTolerance;
}

}  // namespace drumlab
