#include "engine/contact/contact_history.hpp"

#include <algorithm>
#include <atomic>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "engine/counting_sort.hpp"
#include "engine/parallel_copy.hpp"
#include "engine/threads.hpp"
#include "engine/vector_room.hpp"

namespace drumlab {

void ContactList::clear() {
  row_start_.clear();
  col_.clear();
  history_.clear();
  state_.clear();
  clear_dropped();
  cross_receivers_.clear();
  cross_start_.clear();
  cross_k_.clear();
  cross_block_rows_ = 0;
  blocks_rows_ = 0;
}

void ContactList::set_state_size(std::size_t scalars) {
  if (scalars == state_size_) return;
  clear();
  state_size_ = scalars;
}

void ContactList::assign(std::span<const std::size_t> row_start, std::span<const Index> col,
                         std::span<const Vec3> history, std::span<const double> state) {
  const auto bad = [](const char* why) { throw InputError(fmt::format("contact list: {}", why)); };
  if (history.size() != col.size()) bad("history and partner arrays differ in length");
  if (state.size() != col.size() * state_size_) {
    bad("per-contact state does not match the partners and the law's state size");
  }
  if (row_start.empty()) {
    if (!col.empty()) bad("partners without rows");
    clear();
    return;
  }
  const std::size_t rows = row_start.size() - 1;
  if (row_start.front() != 0 || row_start.back() != col.size()) bad("rows do not cover partners");
  // Every row's bounds before any partner is read: a row start past the partners (a damaged
  // checkpoint) would otherwise send the loop below beyond `col`.
  for (std::size_t i = 0; i < rows; ++i) {
    if (row_start[i] > row_start[i + 1] || row_start[i + 1] > col.size()) {
      bad("row starts decrease or pass the partners");
    }
  }
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t k = row_start[i]; k < row_start[i + 1]; ++k) {
      if (col[k] <= i || col[k] >= rows) bad("partner out of range");
      if (k > row_start[i] && col[k] <= col[k - 1]) bad("row not sorted");
    }
  }
  row_start_.assign(row_start.begin(), row_start.end());
  col_.assign(col.begin(), col.end());
  history_.assign(history.begin(), history.end());
  state_.assign(state.begin(), state.end());
  cross_block_rows_ = 0;
  blocks_rows_ = 0;
}

void ContactList::renumber(std::span<const Index> new_index) {
  const std::size_t n = rows();
  const std::size_t m = col_.size();
  // Old arrays become the source; the entries are re-sorted by the new (i, j) through an index.
  col_.swap(old_col_);
  history_.swap(old_history_);
  state_.swap(old_state_);
  // Scratch with room (vector_room.hpp): re-ordering is sampled every sort_every steps, so without
  // it a list slightly longer than at any earlier re-ordering would allocate again.
  resize_with_room(renumbered_, m);
  resize_with_room(by_pair_, m);
  const auto rows_old = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < rows_old; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    for (std::size_t k = row_start_[i]; k < row_start_[i + 1]; ++k) {
      const Index a = new_index[i];
      const Index b = new_index[old_col_[k]];
      renumbered_[k] = a < b ? IndexPair{a, b} : IndexPair{b, a};
      if (b < a) old_history_[k] = -old_history_[k];
    }
  }
  // Counting sort of the entries by their new first index (counting_sort.hpp: a row's entries
  // keep their order whatever the thread count), then each (short, independent) row by the
  // second: O(m), where a comparison sort of all entries took O(m log m).
  constexpr std::size_t kPerThread = 16384;  // below this, one thread
  const std::size_t t_count = counting_sort_by_row(
      m, n, kPerThread, fill_, [&](std::size_t k) { return std::size_t{renumbered_[k].i}; },
      [&](std::size_t k, std::size_t slot) { by_pair_[slot] = k; });
  row_start_.resize(n + 1);
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(n); ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    row_start_[i] = i == 0 ? 0 : fill_[(i - 1) * t_count + t_count - 1];
  }
  row_start_[n] = m;
  resize_with_room(col_, m);
  resize_with_room(history_, m);
  const std::size_t s = state_size_;
  resize_with_room(state_, m * s);
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const std::size_t begin = row_start_[i];
    for (std::size_t a = begin + 1; a < row_start_[i + 1]; ++a) {
      const std::size_t v = by_pair_[a];
      std::size_t b = a;
      for (; b > begin && renumbered_[by_pair_[b - 1]].j > renumbered_[v].j; --b) {
        by_pair_[b] = by_pair_[b - 1];
      }
      by_pair_[b] = v;
    }
    for (std::size_t q = begin; q < row_start_[i + 1]; ++q) {
      col_[q] = renumbered_[by_pair_[q]].j;
      history_[q] = old_history_[by_pair_[q]];
      for (std::size_t c = 0; c < s; ++c) state_[q * s + c] = old_state_[by_pair_[q] * s + c];
    }
  }
  cross_block_rows_ = 0;
}

void ContactList::update(std::span<const IndexPair> pairs, std::size_t n_particles) {
  row_start_.swap(old_row_start_);
  col_.swap(old_col_);
  history_.swap(old_history_);
  build_rows(pairs, n_particles);
  transfer_history();
  if (state_size_ > 0) {
    state_.swap(old_state_);
    transfer_state();
  }
  cross_block_rows_ = 0;
}

void ContactList::index_cross_block(std::size_t block_rows) {
  if (cross_block_rows_ == block_rows) return;
  build_cross_block(block_rows);
  cross_block_rows_ = block_rows;
}

void ContactList::set_row_keys(std::span<const std::uint64_t> keys) {
  row_keys_.assign(keys.begin(), keys.end());
  cross_block_rows_ = 0;
  blocks_rows_ = 0;
}

void ContactList::build_blocks(std::size_t block_rows) {
  const std::size_t n = rows();
  // The blocks follow from the rows' count and keys alone: a list patched or rebuilt keeps them.
  if (blocks_rows_ == block_rows && blocks_n_ == n) return;
  blocks_rows_ = block_rows;
  blocks_n_ = n;
  block_start_.assign(1, 0);
  if (row_keys_.size() == n && n > 0) {  // keyed rows: a block is a run of rows of one key block
    std::uint64_t current = row_keys_[0] / block_rows;
    for (std::size_t i = 1; i < n; ++i) {
      const std::uint64_t block = row_keys_[i] / block_rows;
      if (block != current) block_start_.push_back(i);
      current = block;
    }
  } else {
    for (std::size_t i = block_rows; i < n; i += block_rows) block_start_.push_back(i);
  }
  if (n > 0) block_start_.push_back(n);
  row_block_end_.resize(n);
  const auto blocks = static_cast<std::int64_t>(block_start_.size()) - 1;
  const auto row_count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (row_count >= kParallelMinElements)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::size_t end = block_start_[static_cast<std::size_t>(b) + 1];
    for (std::size_t i = block_start_[static_cast<std::size_t>(b)]; i < end; ++i) {
      row_block_end_[i] = end;
    }
  }
}

namespace {

/// Rows per share of the cross-block index's passes over the rows.
constexpr std::size_t kRowsPerShare = 4096;

/// The shares of n rows: one per kRowsPerShare rows, at least 1, at most the thread count.
std::size_t row_shares(std::size_t n) {
  return std::clamp<std::size_t>(n / kRowsPerShare, 1, static_cast<std::size_t>(max_threads()));
}

/// body(t, begin, end) for each share t of n rows (rows [begin, end)), the shares on the team.
template <class Body>
void for_row_shares(std::size_t n, std::size_t shares, Body&& body) {
  const auto share_total = static_cast<std::int64_t>(shares);
#pragma omp parallel for schedule(static)
  for (std::int64_t s = 0; s < share_total; ++s) {
    const auto t = static_cast<std::size_t>(s);
    body(t, n * t / shares, n * (t + 1) / shares);
  }
}

/// Sorts the cross-block contacts `listed` (increasing k) stably by receiver (their partner,
/// col[k]) into cross_k, and lists the receivers (rows with such contacts, increasing) with the
/// starts of their runs in cross_k. Count: the counting sort's slot type (c < its range).
template <class Count>
void sort_by_receiver(std::span<const std::size_t> listed, std::span<const Index> col,
                      std::size_t n, std::vector<Count>& fill, std::vector<std::size_t>& cross_k,
                      std::vector<Index>& receivers, std::vector<std::size_t>& start,
                      std::vector<std::size_t>& share_count) {
  constexpr std::size_t kContactsPerShare = 32768;  // below this, one thread
  const std::size_t t_count = counting_sort_by_row(
      listed.size(), n, kContactsPerShare, fill, [&](std::size_t q) { return col[listed[q]]; },
      [&](std::size_t q, Count slot) { cross_k[slot] = listed[q]; });
  // Row j ends at fill[j T + T - 1] and starts where row j - 1 ends; the receivers are the rows
  // that are not empty, found per share of rows and placed after the shares before.
  const auto end_of = [&](std::size_t j) -> std::size_t { return fill[j * t_count + t_count - 1]; };
  const auto begin_of = [&](std::size_t j) -> std::size_t { return j == 0 ? 0 : end_of(j - 1); };
  const std::size_t shares = row_shares(n);
  share_count.assign(shares + 1, 0);
  for_row_shares(n, shares, [&](std::size_t t, std::size_t begin, std::size_t end) {
    std::size_t found = 0;
    for (std::size_t j = begin; j < end; ++j) {
      found += end_of(j) > begin_of(j);
    }
    share_count[t + 1] = found;
  });
  std::partial_sum(share_count.begin(), share_count.end(), share_count.begin());
  receivers.resize(share_count.back());
  start.resize(share_count.back() + 1);
  start[0] = 0;
  for_row_shares(n, shares, [&](std::size_t t, std::size_t begin, std::size_t end) {
    std::size_t o = share_count[t];
    for (std::size_t j = begin; j < end; ++j) {
      const std::size_t e = end_of(j);
      if (e == begin_of(j)) continue;
      receivers[o] = static_cast<Index>(j);
      start[++o] = e;
    }
  });
}

}  // namespace

void ContactList::build_cross_block(std::size_t block_rows) {
  build_blocks(block_rows);
  const std::size_t n = rows();
  const std::size_t m = col_.size();
  // Each contact's row, and the contacts that reach past their row's block (the partner's
  // block takes their partner share), counted per share of rows, then listed in increasing k.
  resize_with_room(entry_row_, m);
  const std::size_t shares = row_shares(n);
  share_count_.assign(shares + 1, 0);
  for_row_shares(n, shares, [&](std::size_t t, std::size_t begin, std::size_t end) {
    std::size_t cross = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t block_end = row_block_end_[i];
      for (std::size_t k = row_start_[i]; k < row_start_[i + 1]; ++k) {
        entry_row_[k] = static_cast<Index>(i);
        cross += col_[k] >= block_end;
      }
    }
    share_count_[t + 1] = cross;
  });
  std::partial_sum(share_count_.begin(), share_count_.end(), share_count_.begin());
  const std::size_t cross = share_count_.back();
  resize_with_room(cross_listed_, cross);
  for_row_shares(n, shares, [&](std::size_t t, std::size_t begin, std::size_t end) {
    std::size_t o = share_count_[t];
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t block_end = row_block_end_[i];
      for (std::size_t k = row_start_[i]; k < row_start_[i + 1]; ++k) {
        if (col_[k] >= block_end) cross_listed_[o++] = k;
      }
    }
  });
  // Those contacts by receiver (the partner), each receiver's in increasing k: a stable counting
  // sort of the listed ones only (slots of 4 B while they fit).
  resize_with_room(cross_k_, cross);
  const std::span<const std::size_t> listed(cross_listed_.data(), cross);
  if (cross < std::numeric_limits<std::uint32_t>::max()) {
    sort_by_receiver(listed, col_, n, cross_fill_, cross_k_, cross_receivers_, cross_start_,
                     share_count_);
  } else {
    sort_by_receiver(listed, col_, n, fill_, cross_k_, cross_receivers_, cross_start_,
                     share_count_);
  }
}

void ContactList::build_rows(std::span<const IndexPair> pairs, std::size_t n) {
  // Sorted input (a Verlet list): the row starts and partners in one parallel pass; pair k
  // starts the rows after the previous pair's row up to its own.
  const std::size_t m = pairs.size();
  row_start_.resize(n + 1);
  resize_with_room(col_, m);
  int unsorted = 0;
#pragma omp parallel for schedule(static) reduction(| : unsorted)
  for (std::int64_t kk = 0; kk < static_cast<std::int64_t>(m); ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    const IndexPair& p = pairs[k];
    std::size_t first_row = 0;
    if (k > 0) {
      unsorted |= !(pairs[k - 1] < p);
      first_row = static_cast<std::size_t>(pairs[k - 1].i) + 1;
    }
    if (unsorted == 0) {
      // Relaxed atomic stores (plain moves on x86): a sorted input writes each row start once,
      // but an unsorted one (found unsorted by another thread, and recomputed below) can have
      // two threads write one row start, a data race that ThreadSanitizer reported.
      for (std::size_t r = first_row; r <= p.i; ++r) {
        std::atomic_ref<std::size_t>(row_start_[r]).store(k, std::memory_order_relaxed);
      }
    }
    col_[k] = p.j;
  }
  if (unsorted == 0) {
    for (std::size_t r = m == 0 ? 0 : pairs[m - 1].i + 1; r <= n; ++r) row_start_[r] = m;
    return;
  }
  row_start_.assign(n + 1, 0);
  for (const IndexPair& p : pairs) ++row_start_[p.i + 1];
  for (std::size_t i = 0; i < n; ++i) row_start_[i + 1] += row_start_[i];
  // Counting sort by i.
  fill_.assign(row_start_.begin(), row_start_.end() - 1);
  col_.resize(pairs.size());
  for (const IndexPair& p : pairs) col_[fill_[p.i]++] = p.j;
  // Rows are short (a few contacts): insertion sort by j.
  for (std::size_t i = 0; i < n; ++i) {
    Index* begin = col_.data() + row_start_[i];
    Index* end = col_.data() + row_start_[i + 1];
    for (Index* a = begin + 1; a < end; ++a) {
      const Index v = *a;
      Index* b = a;
      for (; b > begin && *(b - 1) > v; --b) *b = *(b - 1);
      *b = v;
    }
  }
}

namespace {

/// The linear merge of each new row with its old row (both sorted by partner): calls
/// carry(k, ko) for a new entry k whose pair was listed before at ko, fresh(k) for a new pair.
/// Rows are independent, so they are merged in parallel.
template <class Carry, class Fresh>
void merge_rows(std::span<const std::size_t> row_start, std::span<const Index> col,
                std::span<const std::size_t> old_row_start, std::span<const Index> old_col,
                Carry carry, Fresh fresh) {
  const std::size_t old_rows = old_row_start.empty() ? 0 : old_row_start.size() - 1;
  const auto rows = static_cast<std::int64_t>(row_start.empty() ? 0 : row_start.size() - 1);
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < rows; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::size_t ko = i < old_rows ? old_row_start[i] : 0;
    const std::size_t ko_end = i < old_rows ? old_row_start[i + 1] : 0;
    for (std::size_t k = row_start[i]; k < row_start[i + 1]; ++k) {
      const Index j = col[k];
      while (ko < ko_end && old_col[ko] < j) ++ko;
      if (ko < ko_end && old_col[ko] == j) {
        carry(k, ko);
      } else {
        fresh(k);
      }
    }
  }
}

}  // namespace

void ContactList::transfer_history() {
  resize_with_room(history_, col_.size());
  merge_rows(
      row_start_, col_, old_row_start_, old_col_,
      [this](std::size_t k, std::size_t ko) { history_[k] = old_history_[ko]; },
      [this](std::size_t k) { history_[k].setZero(); });
}

// The same merge for the law's scalars (only with state_size() > 0, so a dry scene's update is
// the one from before). old_state_ still matches old_col_ here.
void ContactList::transfer_state() {
  const std::size_t s = state_size_;
  resize_with_room(state_, col_.size() * s);
  merge_rows(
      row_start_, col_, old_row_start_, old_col_,
      [this, s](std::size_t k, std::size_t ko) {
        for (std::size_t c = 0; c < s; ++c) state_[k * s + c] = old_state_[ko * s + c];
      },
      [this, s](std::size_t k) {
        for (std::size_t c = 0; c < s; ++c) state_[k * s + c] = 0.0;
      });
  collect_dropped();
}

// The old entries missing from the new rows (the same merge, the other way round), one thread.
void ContactList::collect_dropped() {
  clear_dropped();
  const std::size_t s = state_size_;
  const std::size_t old_rows = old_row_start_.empty() ? 0 : old_row_start_.size() - 1;
  const std::size_t new_rows = rows();
  for (std::size_t i = 0; i < old_rows; ++i) {
    std::size_t k = i < new_rows ? row_start_[i] : 0;
    const std::size_t k_end = i < new_rows ? row_start_[i + 1] : 0;
    for (std::size_t ko = old_row_start_[i]; ko < old_row_start_[i + 1]; ++ko) {
      const Index j = old_col_[ko];
      while (k < k_end && col_[k] < j) ++k;
      if (k < k_end && col_[k] == j) continue;
      const double* st = &old_state_[ko * s];
      bool held = false;
      for (std::size_t c = 0; c < s; ++c) held = held || st[c] != 0.0;
      if (!held) continue;
      dropped_.push_back({static_cast<Index>(i), j});
      dropped_state_.insert(dropped_state_.end(), st, st + s);
    }
  }
}

std::size_t ContactList::locate(Index i, Index j) const {
  constexpr auto npos = ~std::size_t{0};
  if (static_cast<std::size_t>(i) + 1 >= row_start_.size()) return npos;
  const auto begin = col_.begin() + static_cast<std::ptrdiff_t>(row_start_[i]);
  const auto end = col_.begin() + static_cast<std::ptrdiff_t>(row_start_[i + 1]);
  const auto it = std::lower_bound(begin, end, j);
  if (it == end || *it != j) return npos;
  return static_cast<std::size_t>(it - col_.begin());
}

const Vec3* ContactList::find(Index i, Index j) const {
  const std::size_t k = locate(i, j);
  return k == ~std::size_t{0} ? nullptr : &history_[k];
}

const double* ContactList::find_state(Index i, Index j) const {
  const std::size_t k = locate(i, j);
  return k == ~std::size_t{0} || state_size_ == 0 ? nullptr : &state_[k * state_size_];
}

}  // namespace drumlab
