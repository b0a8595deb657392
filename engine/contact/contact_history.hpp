#pragma once
// The particle-particle contacts of the current step in CSR form, sorted by (i, j), each with its
// tangential displacement (history) carried over from the previous step.
//
// update() takes the search's unordered pair list, counting-sorts it by i into rows, sorts each
// (short) row by j, and copies the history of every pair that was also in the previous list by a
// linear merge of the old and new row: no hashing, and no allocation once the buffers have grown.
#include <cstddef>
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
  /// Follows a re-ordering of the particles: particle i becomes new_index[i]. A pair whose order
  /// flips keeps its history negated (the history is i's displacement relative to j).
  void renumber(std::span<const Index> new_index);
  /// Replaces the list with a saved one (restart). Throws InputError if the arrays do not form a
  /// valid list: row_start non-decreasing from 0 to col.size(), every row sorted with partners
  /// i < j < rows, history.size() == col.size().
  void assign(std::span<const std::size_t> row_start, std::span<const Index> col,
              std::span<const Vec3> history);

  std::size_t size() const { return col_.size(); }
  std::size_t rows() const { return row_start_.empty() ? 0 : row_start_.size() - 1; }
  /// Contacts of particle i are k in [row_start()[i], row_start()[i + 1]), partner col()[k] > i.
  std::span<const std::size_t> row_start() const { return row_start_; }
  std::span<const Index> col() const { return col_; }
  /// Builds the partner index below if the list changed since it was last built (only the
  /// multi-threaded force loop needs it, so one thread skips the work).
  void index_partners();
  /// Contacts in which particle j is the partner: k = partner_contacts()[q] for q in
  /// [partner_start()[j], partner_start()[j + 1]), increasing k. Valid after index_partners().
  std::span<const std::size_t> partner_start() const { return partner_start_; }
  std::span<const std::size_t> partner_contacts() const { return partner_k_; }
  std::span<Vec3> history() { return history_; }
  std::span<const Vec3> history() const { return history_; }
  /// History of pair (i, j), i < j, or nullptr if it is not a contact (tests, diagnostics).
  const Vec3* find(Index i, Index j) const;

 private:
  void build_rows(std::span<const IndexPair> pairs, std::size_t n);
  void transfer_history();
  void build_partners();

  std::vector<std::size_t> row_start_;
  std::vector<Index> col_;
  std::vector<Vec3> history_;
  std::vector<std::size_t> old_row_start_;
  std::vector<Index> old_col_;
  std::vector<Vec3> old_history_;
  std::vector<std::size_t> fill_;  // scratch: next free slot per row
  std::vector<std::size_t> partner_start_;
  std::vector<std::size_t> partner_k_;
  bool partners_current_ = false;      ///< partner_start_, partner_k_ match the list
  std::vector<IndexPair> renumbered_;  // scratch of renumber()
  std::vector<std::size_t> by_pair_;
};

}  // namespace drumlab
