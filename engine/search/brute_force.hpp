#pragma once
// O(N^2) search over all pairs: the oracle every other method is tested against.
#include "engine/search/contact_search.hpp"

namespace drumlab {

class BruteForceSearch final : public ContactSearch {
 public:
  std::string_view name() const override { return "brute"; }
  std::string_view description() const override {
    return "all N(N-1)/2 pairs tested (test oracle, O(N^2))";
  }
  void find_pairs(const SearchInput& in, std::vector<IndexPair>& out) override;
};

}  // namespace drumlab
