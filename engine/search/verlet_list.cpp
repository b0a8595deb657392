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
#include "engine/vector_room.hpp"

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

/// x as seen from a frame turned by `angle` about the z axis.
struct FrameTurn {
  double c = 1.0, s = 0.0;
  explicit FrameTurn(double angle) : c(std::cos(angle)), s(std::sin(angle)) {}
  Vec3 operator()(const Vec3& x) const {
    return {c * x.x() + s * x.y(), c * x.y() - s * x.x(), x.z()};
  }
};

/// The skin the displacements may close, a hair under the skin: the references, turned into the
/// frame, carry a rounding of ~1e-16 of their distance from the axis.
double usable_skin(double skin) {
  return skin * (1.0 - 1e-9);
}

/// The two largest of a set of squared displacements (NaN counts as infinite), and the largest
/// squared distance from the z axis.
struct TopTwo {
  double first = 0.0, second = 0.0, axis2 = 0.0;
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
    axis2 = std::max(axis2, o.axis2);
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

/// out = the pairs of `list` that join no particle marked in `moved`, merged with `add` (both
/// sorted, distinct; every pair of `add` joins a marked particle, so the two sets are disjoint):
/// the moved particles' old pairs replaced by their new ones. Rows of first indices in contiguous
/// shares per thread: each share's size sets its place in `out`.
void splice_pairs(std::span<const IndexPair> list, std::span<const IndexPair> add,
                  std::span<const std::uint8_t> moved, std::size_t n, std::vector<IndexPair>& out,
                  std::vector<std::size_t>& cuts) {
  const int threads = list.size() >= kParallelMinElements ? max_threads() : 1;
  const auto shares = static_cast<std::size_t>(threads);
  // cuts: [0, shares] the shares' first entries in list, [shares + 1, 2 shares + 1] in add,
  // [2 shares + 2, 3 shares + 2] in out.
  cuts.assign(3 * (shares + 1), 0);
  const auto first_of_row = [](std::span<const IndexPair> pairs, std::size_t row) {
    return static_cast<std::size_t>(
        std::lower_bound(pairs.begin(), pairs.end(), row,
                         [](const IndexPair& p, std::size_t i) { return p.i < i; }) -
        pairs.begin());
  };
  for (std::size_t s = 0; s <= shares; ++s) {
    const std::size_t row = n * s / shares;
    cuts[s] = s == shares ? list.size() : first_of_row(list, row);
    cuts[shares + 1 + s] = s == shares ? add.size() : first_of_row(add, row);
  }
  std::size_t* at = cuts.data() + 2 * (shares + 1);
  const auto kept = [&](const IndexPair& p) { return (moved[p.i] | moved[p.j]) == 0; };
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int share = 0; share < threads; ++share) {
    const auto s = static_cast<std::size_t>(share);
    std::size_t count = cuts[shares + 2 + s] - cuts[shares + 1 + s];
    for (std::size_t k = cuts[s]; k < cuts[s + 1]; ++k) count += kept(list[k]);
    at[s + 1] = count;  // the share's size, summed into places below
  }
  for (std::size_t s = 0; s < shares; ++s) at[s + 1] += at[s];
  resize_with_room(out, at[shares]);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int share = 0; share < threads; ++share) {
    const auto s = static_cast<std::size_t>(share);
    const IndexPair* b = add.data() + cuts[shares + 1 + s];
    const IndexPair* const b_end = add.data() + cuts[shares + 2 + s];
    IndexPair* o = out.data() + at[s];
    for (std::size_t k = cuts[s]; k < cuts[s + 1]; ++k) {
      const IndexPair p = list[k];
      if (!kept(p)) continue;
      while (b < b_end && *b < p) *o++ = *b++;
      *o++ = p;
    }
    while (b < b_end) *o++ = *b++;
  }
}

}  // namespace

VerletListSearch::Need VerletListSearch::needs_rebuild(const SearchInput& in) {
  const std::size_t n = in.position.size();
  if (n != reference_.size() || in.margin != margin_ || in.period_z.value_or(0.0) != period_ ||
      !parallel_equal<double>(radius_, in.radius)) {
    return Need::rebuild;
  }
  // No particle moved more than half the skin: no pair can have closed it.
  if (moved_ <= 0.5 * usable_skin(skin_)) return Need::nothing;
  ++checks_;
  TopTwo top;
  const FrameTurn turn(in.frame_angle);
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for reduction(top_two : top) schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    const Vec3& x = in.position[i];
    top.add(distance_squared(turn(x), reference_[i], period_));
    top.axis2 = std::max(top.axis2, x.x() * x.x() + x.y() * x.y());
  }
  // A pair left out of the list was more than cut-off + skin apart at its references; it has
  // closed by at most d_i + d_j <= (largest + second largest displacement). A non-finite position
  // gives an infinite displacement: the rebuild's input check then reports it.
  moved_ = std::sqrt(top.first);
  axis_distance_ = std::sqrt(top.axis2);
  return std::sqrt(top.first) + std::sqrt(top.second) <= usable_skin(skin_) ? Need::nothing
                                                                            : Need::motion;
}

bool VerletListSearch::patch(const SearchInput& in) {
  // Patched: the particles that moved more than this share of the skin (after the patch the two
  // largest moves sum to at most half the skin). A full rebuild instead when more than one in
  // kMostPatched moved that far, or the list has grown by a quarter since the rebuild.
  constexpr double kShare = 0.25;
  constexpr std::size_t kMostPatched = 8;
  const std::size_t n = reference_.size();
  if (patch_min_particles_ == 0 || n < patch_min_particles_ ||
      4 * list_.size() > 5 * listed_at_rebuild_) {
    return false;
  }
  const FrameTurn turn(in.frame_angle);
  const double limit = kShare * usable_skin(skin_);
  // The particles that moved that far, ascending: each thread scans a contiguous share of them,
  // the shares joined in order (the same set for any thread count).
  const int threads = n >= kParallelMinElements ? max_threads() : 1;
  moved_shares_.resize(static_cast<std::size_t>(threads));
  double rest2 = 0.0;
  bool finite = true;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : rest2) \
    reduction(&& : finite)
  for (int share = 0; share < threads; ++share) {
    std::vector<Index>& moved = moved_shares_[static_cast<std::size_t>(share)];
    moved.clear();
    const std::size_t begin =
        n * static_cast<std::size_t>(share) / static_cast<std::size_t>(threads);
    const std::size_t end =
        n * static_cast<std::size_t>(share + 1) / static_cast<std::size_t>(threads);
    for (std::size_t i = begin; i < end; ++i) {
      const double d2 = distance_squared(turn(in.position[i]), reference_[i], period_);
      if (d2 <= limit * limit) {
        rest2 = std::max(rest2, d2);
        continue;
      }
      // Not finite (d2 NaN lands here too): the rebuild's input check names the particle.
      if (!in.position[i].allFinite()) finite = false;
      if (moved.size() <= n / kMostPatched) moved.push_back(static_cast<Index>(i));
    }
  }
  patched_.clear();
  for (const auto& moved : moved_shares_)
    patched_.insert(patched_.end(), moved.begin(), moved.end());
  if (!finite || patched_.size() > n / kMostPatched) return false;
  for (const Index f : patched_) reference_[f] = turn(in.position[f]);
  patcher_.find(reference_, radius_, patched_, margin_ + skin_, period_, patch_pairs_);
  // Their old pairs go, their pairs at the new references come: a pair dropped is more than
  // cut-off + skin apart at its references, so it does not touch now (the partner moved less than
  // a quarter of the skin), and the list does not keep pairs that no longer need listing.
  if (moved_flag_.size() != n) moved_flag_.assign(n, 0);
  for (const Index f : patched_) moved_flag_[f] = 1;
  splice_pairs(list_, patch_pairs_, moved_flag_, n, scratch_pairs_, splice_cuts_);
  for (const Index f : patched_) moved_flag_[f] = 0;
  list_.swap(scratch_pairs_);
  count_rows(list_, n, listed_per_particle_);
  moved_ = std::sqrt(rest2);
  ++patches_;
  return true;
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
  // The references in the turning frame (at angle 0 the positions themselves, to the bit).
  reference_.resize(n);
  const FrameTurn turn(in.frame_angle);
  double axis2 = 0.0;
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) reduction(max : axis2) if (count >= kParallelMinElements)
  for (std::int64_t i = 0; i < count; ++i) {
    const Vec3& x = in.position[i];
    reference_[i] = turn(x);
    axis2 = std::max(axis2, x.x() * x.x() + x.y() * x.y());
  }
  parallel_assign<double>(radius_, in.radius);
  margin_ = in.margin;
  period_ = in.period_z.value_or(0.0);
  moved_ = 0.0;
  axis_distance_ = std::sqrt(axis2);
  angle_ = in.frame_angle;
  listed_at_rebuild_ = list_.size();
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
  // In the turning frame a particle moves by at most its own move plus the frame's turn times its
  // distance from the axis (which grows by at most its move).
  const double step = moved >= 0.0 ? moved : kUnknownMotion;  // NaN or negative: unknown
  const double turned = std::abs(in.frame_angle - angle_);
  angle_ = in.frame_angle;
  axis_distance_ += step;
  moved_ += step;
  if (turned > 0.0) moved_ += turned * axis_distance_;
  // The full input check runs with every rebuild (in the builder); between rebuilds the listed
  // pairs stay exact, and a non-finite position forces a rebuild (see needs_rebuild).
  const Need need = needs_rebuild(in);
  const bool patched = need == Need::motion && patch(in);
  const bool rebuilt = need != Need::nothing && !patched;
  if (rebuilt) rebuild(in);
  if (patched) listed_only_ = false;  // the listed pairs changed
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
  return rebuilt || patched;
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
      "Verlet list: {} rebuilds in {} calls (every {:.1f} calls), {} patches, displacements "
      "checked in {} calls, {:.2f} listed pairs/particle",
      rebuilds_, calls_,
      rebuilds_ > 0 ? static_cast<double>(calls_) / static_cast<double>(rebuilds_) : 0.0, patches_,
      checks_, static_cast<double>(list_.size()) / n);
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
