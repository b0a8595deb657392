#pragma once
// The particle-particle contacts of the current step in CSR form, sorted by (i, j), each with its
// tangential displacement (history) carried over from the previous step.
//
// update() takes the search's unordered pair list, counting-sorts it by i into rows, sorts each
// (short) row by j, and copies the history of every pair that was also in the previous list by a
// linear merge of the old and new row: no hashing, and no allocation once the buffers have grown.
//
// Besides the tangential history, a contact can carry `state_size()` scalars that a law part
// declares (ContactModel::pair_state_size(), e.g. a liquid bridge's volume). They follow the same
// paths as the history: carried over by the merge at update(), moved (not negated) by renumber(),
// saved and restored through assign(). Contact k's scalars are state()[k * state_size() + c].
// With state_size() == 0 (a dry scene) none of this runs: the dry paths are the ones from before.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/search/contact_search.hpp"
#include "engine/types.hpp"

namespace drumlab {

class ContactList {
 public:
  /// Replaces the contacts with `pairs` (each i < j < n_particles, no duplicates, any order).
  /// Pairs present before keep their history; new pairs start with zero displacement.
  void update(std::span<const IndexPair> pairs, std::size_t n_particles);
  /// Forgets every contact and its history.
  void clear();
  /// Scalars kept per contact (see above); changing it forgets every contact.
  void set_state_size(std::size_t scalars);
  std::size_t state_size() const { return state_size_; }
  /// Follows a re-ordering of the particles: particle i becomes new_index[i]. A pair whose order
  /// flips keeps its history negated (the history is i's displacement relative to j).
  void renumber(std::span<const Index> new_index);
  /// Replaces the list with a saved one (restart). Throws InputError if the arrays do not form a
  /// valid list: row_start non-decreasing from 0 to col.size(), every row sorted with partners
  /// i < j < rows, history.size() == col.size(), state.size() == col.size() * state_size().
  void assign(std::span<const std::size_t> row_start, std::span<const Index> col,
              std::span<const Vec3> history, std::span<const double> state = {});

  std::size_t size() const { return col_.size(); }
  std::size_t rows() const { return row_start_.empty() ? 0 : row_start_.size() - 1; }
  /// Contacts of particle i are k in [row_start()[i], row_start()[i + 1]), partner col()[k] > i.
  std::span<const std::size_t> row_start() const { return row_start_; }
  std::span<const Index> col() const { return col_; }
  /// Builds the row blocks and the cross-block index below if the list or `block_rows` changed
  /// since they were last built. Rows are grouped in blocks of `block_rows` by their key (see
  /// set_row_keys; by default row i's key is i, so block b holds rows [b, b + 1) x block_rows); a
  /// contact is "cross-block" if its partner j lies in another block than i (always a later one).
  void index_cross_block(std::size_t block_rows);
  /// Gives each row a key (increasing with the row; empty: the row index itself). A rank of an
  /// MPI run keys its rows with the serial run's slots of its particles, so its blocks group
  /// the particles as the serial run's blocks do and every force is summed in the serial order.
  void set_row_keys(std::span<const std::uint64_t> keys);
  /// The row blocks (valid after index_cross_block): block b is rows [block_start()[b],
  /// block_start()[b + 1]); row_block_end()[i] is the end of row i's block.
  std::span<const std::size_t> block_start() const { return block_start_; }
  std::span<const std::size_t> row_block_end() const { return row_block_end_; }
  /// The row of every contact: entry_rows()[k] = i for k in [row_start()[i], row_start()[i + 1])
  /// (the pair loop splits chunks of entries across row ends). Valid after index_cross_block().
  std::span<const Index> entry_rows() const { return entry_row_; }
  /// The particles that are the partner of some cross-block contact, increasing; for the r-th,
  /// its cross-block contacts are k = cross_contacts()[q] for q in [cross_start()[r],
  /// cross_start()[r + 1]), increasing k. Valid after index_cross_block().
  std::span<const Index> cross_receivers() const { return cross_receivers_; }
  std::span<const std::size_t> cross_start() const { return cross_start_; }
  std::span<const std::size_t> cross_contacts() const { return cross_k_; }
  std::span<Vec3> history() { return history_; }
  std::span<const Vec3> history() const { return history_; }
  std::span<double> state() { return state_; }
  std::span<const double> state() const { return state_; }
  /// History of pair (i, j), i < j, or nullptr if it is not a contact (tests, diagnostics).
  const Vec3* find(Index i, Index j) const;
  /// The state_size() scalars of pair (i, j), i < j, or nullptr if it is not a contact.
  const double* find_state(Index i, Index j) const;
  /// The contacts the last update() dropped (listed before, not now) whose state held a non-zero
  /// scalar, by increasing (i, j), and their state (state_size() each): a law part that keeps
  /// something in its state (a bridge's liquid) settles them. Emptied by the next update() and
  /// by clear_dropped(); always empty with state_size() == 0.
  std::span<const IndexPair> dropped() const { return dropped_; }
  std::span<const double> dropped_state() const { return dropped_state_; }
  void clear_dropped() {
    dropped_.clear();
    dropped_state_.clear();
  }

 private:
  void build_rows(std::span<const IndexPair> pairs, std::size_t n);
  void transfer_history();
  void transfer_state();
  void collect_dropped();
  /// Contact k of the list, or npos if (i, j) is not listed.
  std::size_t locate(Index i, Index j) const;
  void build_cross_block(std::size_t block_rows);
  void build_blocks(std::size_t block_rows);

  std::vector<std::size_t> row_start_;
  std::vector<Index> col_;
  std::vector<Vec3> history_;
  std::vector<std::size_t> old_row_start_;
  std::vector<Index> old_col_;
  std::vector<Vec3> old_history_;
  std::size_t state_size_ = 0;
  std::vector<double> state_;
  std::vector<double> old_state_;
  std::vector<IndexPair> dropped_;
  std::vector<double> dropped_state_;
  std::vector<std::size_t> fill_;  // scratch: next free slot per row
  std::vector<Index> entry_row_;
  std::vector<Index> cross_receivers_;
  std::vector<std::size_t> cross_start_;
  std::vector<std::size_t> cross_k_;
  std::vector<std::size_t> cross_listed_;  // scratch: the cross-block contacts, increasing k
  std::vector<std::uint32_t> cross_fill_;  // scratch: their counting sort's slots
  std::vector<std::size_t> share_count_;   // scratch: per share of rows, then offsets
  std::size_t cross_block_rows_ = 0;       ///< block size of the cross-block index; 0: out of date
  std::vector<std::uint64_t> row_keys_;
  std::vector<std::size_t> block_start_;
  std::size_t blocks_rows_ = 0;  ///< block size of block_start_, row_block_end_; 0: out of date
  std::size_t blocks_n_ = 0;     ///< the rows they were built for
  std::vector<std::size_t> row_block_end_;
  std::vector<IndexPair> renumbered_;  // scratch of renumber()
  std::vector<std::size_t> by_pair_;
};

}  // namespace drumlab
