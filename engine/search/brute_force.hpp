#pragma once
// O(N^2) search over all pairs: the oracle every other method is tested against.
#include "engine/search/contact_search.hpp"

namespace drumlab {

class BruteForceSearch final : public ContactSearch {
 public:
  std::string_view name() const override { return "brute"; }
  std::string_view description() const override;
  void find_pairs(const SearchInput& in, std::vector<IndexPair>& out) override;
  /// Candidates: every particle after i in storage order (the pairs i tests); no cells.
  SearchVisit visit(Index i, const SearchInput& in) const override;
};

}  // namespace drumlab
