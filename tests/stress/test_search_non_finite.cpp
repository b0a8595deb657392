// A state that went bad between two stability checks reaches the contact search with huge,
// infinite or NaN coordinates: every method must either find pairs or throw InputError (which the
// simulation reports as "unstable: ... contact search failed"), never crash or hang.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "engine/search/contact_search.hpp"

namespace drumlab {
namespace {

TEST(SearchNonFinite, EveryMethodThrowsOrCopesNeverCrashes) {
  const double bad_values[] = {std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity(), 1e300};
  for (const double bad : bad_values) {
    for (const auto& name : search_method_names()) {
      std::vector<Vec3> x;
      std::vector<double> r;
      for (int i = 0; i < 50; ++i) {
        x.emplace_back(0.01 * (i % 7), 0.01 * (i / 7), 0.005);
        r.push_back(0.004);
      }
      x[17] = Vec3(bad, 0.02, 0.005);
      SearchInput in;
      in.position = x;
      in.radius = r;
      std::vector<IndexPair> pairs;
      const auto search = make_search(name);
      try {
        search->find_pairs(in, pairs);
        for (const IndexPair& p : pairs) EXPECT_TRUE(p.i != 17 && p.j != 17) << name << " " << bad;
      } catch (const InputError&) {
        SUCCEED();
      }
    }
  }
}

}  // namespace
}  // namespace drumlab
