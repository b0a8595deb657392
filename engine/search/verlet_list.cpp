#include "engine/search/verlet_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "engine/parallel_copy.hpp"
#include "engine/search/search_input.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/spatial_order.hpp"
#include "engine/threads.hpp"

namespace drumlab {

VerletListSearch::VerletListSearch(std::unique_ptr<ContactSearch> builder, double skin_factor)
    : builder_(std::move(builder)), skin_factor_(skin_factor) {
  if (!(skin_factor > 0.0)) {
    throw InputError(fmt::format("verlet: skin factor must be positive, got {}", skin_factor));
  }
  name_ = verlet_method_name(builder_->name());
  description_ = fmt::format(
      "Verlet list, skin {} R_min, rebuilt by {} when the two largest moves sum to > skin",
      skin_factor_, builder_->name());
}

void VerletListSearch::filter(const SearchInput& in, std::vector<IndexPair>& out) {
  // Contiguous slices of the sorted list per thread, joined in order: the output stays sorted
  // and does not depend on the thread count.
  const std::size_t m = list_.size();
  const double margin = in.margin + kTouchTolerance;
  // Slices by number, not by thread: a team smaller than asked for (a nested region,
  // OMP_DYNAMIC on a busy machine) still filters every slice.
  const int threads = slices_.prepare(max_threads());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int share = 0; share < threads; ++share) {
    const auto t = static_cast<std::size_t>(share);
    std::vector<IndexPair>& slice = slices_.slice(share);
    const std::size_t begin = m * t / static_cast<std::size_t>(threads);
    const std::size_t end = m * (t + 1) / static_cast<std::size_t>(threads);
    for (std::size_t k = begin; k < end; ++k) {
      const IndexPair p = list_[k];
      const double cut = in.radius[p.i] + in.radius[p.j] + margin;
      if (distance_squared(in.position[p.i], in.position[p.j], period_) <= cut * cut) {
        slice.push_back(p);
      }
    }
  }
  out.clear();
  slices_.join(out);
}

namespace {

/// The two largest of a set of squared displacements; NaN counts as infinite.
struct TopTwo {
  double first = 0.0, second = 0.0;
  void add(double d2) {
    if (std::isnan(d2)) d2 = std::numeric_limits<double>::infinity();
    if (d2 > first) {
      second = first;
      first = d2;
    } else if (d2 > second) {
      second = d2;
    }
  }
  void merge(const TopTwo& o) {
    add(o.first);
    add(o.second);
  }
};
#pragma omp declare reduction(top_two:TopTwo : omp_out.merge(omp_in))

/// The entries of each first index of a list sorted by i, in parallel: each chunk of rows finds
/// its first entry by bisection and walks its rows from there.
void count_rows(std::span<const IndexPair> list, std::size_t n, std::vector<std::uint32_t>& out) {
  constexpr std::size_t kRowsPerChunk = 4096;
  out.resize(n);
  const std::size_t m = list.size();
  const auto chunks = static_cast<std::int64_t>((n + kRowsPerChunk - 1) / kRowsPerChunk);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::size_t begin = static_cast<std::size_t>(c) * kRowsPerChunk;
    const std::size_t end = std::min(n, begin + kRowsPerChunk);
    std::size_t k = static_cast<std::size_t>(
        std::lower_bound(list.begin(), list.end(), begin,
                         [](const IndexPair& p, std::size_t i) { return p.i < i; }) -
        list.begin());
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t start = k;
      while (k < m && list[k].i == i) ++k;
      out[i] = static_cast<std::uint32_t>(k - start);
    }
  }
}

}  // namespace

bool VerletListSearch::needs_rebuild(const SearchInput& in) {
  const std::size_t n = in.position.size();
  if (n != reference_.size() || in.margin != margin_ || in.period_z.value_or(0.0) != period_ ||
      !parallel_equal<double>(radius_, in.radius)) {
    return true;
  }
  // No particle moved more than half the skin: no pair can have closed it.
  if (moved_ <= 0.5 * skin_) return false;
  ++checks_;
  TopTwo top;
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for reduction(top_two : top) schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    top.add(distance_squared(in.position[i], reference_[i], period_));
  }
  // A pair left out of the list was more than cut-off + skin apart at the build; it has closed by
  // at most d_i + d_j <= (largest + second largest displacement). A non-finite position gives an
  // infinite displacement: the rebuild's input check then reports it.
  moved_ = std::sqrt(top.first);
  return !(std::sqrt(top.first) + std::sqrt(top.second) <= skin_);
}

void VerletListSearch::rebuild(const SearchInput& in) {
  validate_search_input(in);
  const std::size_t n = in.position.size();
  const double rmin = n == 0 ? 0.0 : *std::min_element(in.radius.begin(), in.radius.end());
  skin_ = skin_factor_ * rmin;
  SearchInput wide = in;
  wide.margin = in.margin + skin_;
  builder_->find_pairs(wide, list_);
  // Sorted by (i, j), the filtered output is sorted too, which the contact list builds fastest.
  sort_pairs(list_, n, scratch_pairs_, scratch_counts_);
  count_rows(list_, n, listed_per_particle_);
  parallel_assign<Vec3>(reference_, in.position);
  parallel_assign<double>(radius_, in.radius);
  margin_ = in.margin;
  period_ = in.period_z.value_or(0.0);
  moved_ = 0.0;
  builder_current_ = true;
  ++rebuilds_;
}

void VerletListSearch::renumber(std::span<const Index> order, std::span<const Index> new_index) {
  if (reference_.size() != order.size()) {  // no list for these particles: rebuild anyway
    invalidate();
    return;
  }
  const auto listed = static_cast<std::int64_t>(list_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < listed; ++k) {
    IndexPair& p = list_[static_cast<std::size_t>(k)];
    const Index a = new_index[p.i];
    const Index b = new_index[p.j];
    p = a < b ? IndexPair{a, b} : IndexPair{b, a};
  }
  const std::size_t n = order.size();
  sort_pairs(list_, n, scratch_pairs_, scratch_counts_);
  apply_order(reference_, order, scratch_positions_);
  apply_order(radius_, order, scratch_radii_);
  count_rows(list_, n, listed_per_particle_);
  listed_only_ = false;  // the per-particle counters follow at the next call
  builder_current_ = false;
}

bool VerletListSearch::refresh(const SearchInput& in, double moved) {
  const auto t0 = SearchClock::now();
  if (in.position.size() != in.radius.size()) validate_search_input(in);  // throws
  ++calls_;
  moved_ += moved >= 0.0 ? moved : kUnknownMotion;  // NaN or negative: unknown
  // The full input check runs with every rebuild (in the builder); between rebuilds the listed
  // pairs stay exact, and a non-finite position forces a rebuild (see needs_rebuild).
  const bool rebuilt = needs_rebuild(in);
  if (rebuilt) rebuild(in);
  // Per particle, a call tests its listed pairs, plus the builder's work on a rebuild. Between
  // rebuilds that does not change: the arrays are rewritten once, not on every call.
  if (rebuilt) {
    counters_ = builder_->counters();
    const auto cells = builder_->cells_visited_per_particle();
    const auto tests = builder_->pairs_tested_per_particle();
    parallel_assign<std::uint32_t>(cells_per_particle_, cells);
    tests_per_particle_.resize(tests.size());
    const auto count = static_cast<std::int64_t>(tests.size());
#pragma omp parallel for schedule(static) if (count >= kParallelMinElements)
    for (std::int64_t i = 0; i < count; ++i) {
      tests_per_particle_[i] = tests[i] + listed_per_particle_[i];
    }
    listed_only_ = false;
  } else {
    counters_ = SearchCounters{};
    if (!listed_only_) {
      parallel_fill<std::uint32_t>(cells_per_particle_, in.position.size(), 0);
      parallel_assign<std::uint32_t>(tests_per_particle_, listed_per_particle_);
      listed_only_ = true;
    }
  }
  counters_.pairs_tested += list_.size();
  counters_.pairs_found = 0;
  timings_ = {seconds_since(t0), 0.0};
  return rebuilt;
}

void VerletListSearch::find_pairs(const SearchInput& in, std::vector<IndexPair>& out) {
  refresh(in);
  const auto t0 = SearchClock::now();
  filter(in, out);
  counters_.pairs_found = out.size();
  timings_.visit = seconds_since(t0);
}

std::string VerletListSearch::report() const {
  const double n = std::max<double>(1.0, static_cast<double>(reference_.size()));
  return fmt::format(
      "Verlet list: {} rebuilds in {} calls (every {:.1f} calls), displacements checked in {} "
      "calls, {:.2f} listed pairs/particle",
      rebuilds_, calls_,
      rebuilds_ > 0 ? static_cast<double>(calls_) / static_cast<double>(rebuilds_) : 0.0, checks_,
      static_cast<double>(list_.size()) / n);
}

SearchVisit VerletListSearch::visit(Index i, const SearchInput& in) const {
  const std::size_t n = reference_.size();
  if (in.position.size() != n || in.radius.size() != n) {
    throw InputError(fmt::format("visit: {} holds a list of {} particles, not {}", name_, n,
                                 in.position.size()));
  }
  if (i >= n) throw InputError(fmt::format("visit: particle {} of {}", i, n));
  SearchVisit v;
  v.kind = SearchVisit::Kind::list;
  v.particle = i;
  const double margin = in.margin + kTouchTolerance;
  const double period = in.period_z.value_or(0.0);
  for (const IndexPair& p : list_) {  // O(list): on demand only
    if (p.i != i && p.j != i) continue;
    const Index j = p.i == i ? p.j : p.i;
    if (p.i == i) ++v.pairs_tested;  // the pairs under i: its row of the list
    v.candidates.push_back(j);
    const double cut = in.radius[i] + in.radius[j] + margin;
    if (distance_squared(in.position[i], in.position[j], period) <= cut * cut) {
      v.contacts.push_back(j);
    }
  }
  if (builder_current_) {
    SearchInput wide = in;
    wide.margin = margin_ + skin_;
    SearchVisit built = builder_->visit(i, wide);
    for (VisitedCells& g : built.grids) {
      g.label = fmt::format("builder {}, last rebuild{}", builder_->name(),
                            g.label == builder_->name() ? "" : ": " + g.label);
      v.grids.push_back(std::move(g));
    }
  }
  v.note = fmt::format(
      "Verlet list: {} listed partners ({} under this particle), {} within the "
      "margin; skin {:.2g} mm{}",
      v.candidates.size(), v.pairs_tested, v.contacts.size(), 1000.0 * skin_,
      builder_current_ ? "" : "; re-ordered since the last rebuild");
  return v;
}

}  // namespace drumlab
