// ContactSearch::visit, for every method: one particle's replayed search. Against the brute-force
// oracle: every true pair is a candidate of one of its two particles (of exactly one for the grids
// and brute force, which test each pair once), the contacts are the candidates within the
// cut-off, and together they are the pair set; the counts equal the engine's per-particle counters
// of the call replayed.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "engine/search/contact_search.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab {
namespace {

struct Cloud {
  std::vector<Vec3> x;
  std::vector<double> r;
};

/// Random spheres in a box, three radii (ratio 3), dense enough for many contacts.
Cloud random_cloud(std::size_t n, const Vec3& size, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double radii[3] = {0.005, 0.01, 0.015};
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.x.emplace_back(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z());
    c.r.push_back(radii[i % 3]);
  }
  return c;
}

std::vector<std::string> every_method() {
  std::vector<std::string> names;
  for (const SearchMethodInfo& m : search_methods()) {
    names.emplace_back(m.name);
    if (m.builds_verlet) names.push_back(verlet_method_name(m.name));
  }
  return names;
}

class SearchVisitOf : public ::testing::TestWithParam<std::string> {
 protected:
  void check(const Cloud& c, double margin, std::optional<double> period) {
    const SearchInput in{c.x, c.r, margin, std::nullopt, period};
    std::vector<IndexPair> expected;
    make_search("brute")->find_pairs(in, expected);
    std::sort(expected.begin(), expected.end());
    ASSERT_FALSE(expected.empty());

    auto search = make_search(GetParam());
    std::vector<IndexPair> out;
    search->find_pairs(in, out);
    // A Verlet list's first call adds its builder's work to the counters; the second call (no
    // motion, no rebuild) counts the listed pairs alone, which is what visit() reports.
    if (GetParam().starts_with("verlet")) search->find_pairs(in, out);

    std::set<IndexPair> tested, found;
    const auto cells = search->cells_visited_per_particle();
    const auto tests = search->pairs_tested_per_particle();
    for (Index i = 0; i < c.x.size(); ++i) {
      const SearchVisit v = search->visit(i, in);
      ASSERT_EQ(v.particle, i);
      ASSERT_EQ(v.cells_visited, cells[i]) << "particle " << i;
      ASSERT_EQ(v.pairs_tested, tests[i]) << "particle " << i;
      const bool list = v.kind == SearchVisit::Kind::list;
      if (!list) {
        ASSERT_EQ(v.candidates.size(), v.pairs_tested) << "particle " << i;
      }
      std::size_t drawn_cells = 0;
      for (const VisitedCells& g : v.grids) drawn_cells += g.count();
      if (v.kind == SearchVisit::Kind::cells || v.kind == SearchVisit::Kind::levels) {
        ASSERT_EQ(drawn_cells, v.cells_visited) << "particle " << i;
        ASSERT_TRUE(v.grids.front().has_own);
      }
      for (Index j : v.candidates) {
        ASSERT_NE(j, i);
        const IndexPair p = i < j ? IndexPair{i, j} : IndexPair{j, i};
        const bool first = tested.insert(p).second;
        if (!list) {
          ASSERT_TRUE(first) << "pair tested twice: " << p.i << " " << p.j;
        }
      }
      for (Index j : v.contacts) {
        ASSERT_NE(std::find(v.candidates.begin(), v.candidates.end(), j), v.candidates.end());
        found.insert(i < j ? IndexPair{i, j} : IndexPair{j, i});
      }
    }
    for (const IndexPair& p : expected) {
      ASSERT_TRUE(tested.count(p)) << "true contact " << p.i << " " << p.j << " never tested";
    }
    EXPECT_EQ(std::vector<IndexPair>(found.begin(), found.end()), expected);
    EXPECT_THROW(search->visit(static_cast<Index>(c.x.size()), in), InputError);
  }
};

TEST_P(SearchVisitOf, ClosedBox) {
  check(random_cloud(900, Vec3(0.25, 0.2, 0.1), 11), 0.0, std::nullopt);
}

TEST_P(SearchVisitOf, PeriodicZWithAMargin) {
  check(random_cloud(900, Vec3(0.25, 0.2, 0.2), 12), 0.002, 0.2);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, SearchVisitOf, ::testing::ValuesIn(every_method()),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), ':', '_');
                           return name;
                         });

TEST(SearchVisit, KindsSayWhatWasVisited) {
  const Cloud c = random_cloud(300, Vec3(0.2, 0.2, 0.1), 13);
  const SearchInput in{c.x, c.r, 0.0, std::nullopt, std::nullopt};
  std::vector<IndexPair> out;
  auto brute = make_search("brute");
  brute->find_pairs(in, out);
  const SearchVisit b = brute->visit(0, in);
  EXPECT_EQ(b.kind, SearchVisit::Kind::all);
  EXPECT_TRUE(b.grids.empty());
  EXPECT_EQ(b.candidates.size(), c.x.size() - 1);
  EXPECT_NE(b.note.find("N-1 = 299"), std::string::npos) << b.note;

  auto ml = make_search("mlgrid");
  ml->find_pairs(in, out);
  // A particle of the largest size searches its own level and both smaller ones.
  const SearchVisit m = ml->visit(2, in);
  EXPECT_EQ(m.kind, SearchVisit::Kind::levels);
  ASSERT_EQ(m.grids.size(), 3u);
  EXPECT_TRUE(m.grids[0].has_own);
  EXPECT_FALSE(m.grids[1].has_own);
  EXPECT_GT(m.grids[0].geometry.cell_xy, m.grids[1].geometry.cell_xy);

  auto verlet = make_search("verlet:m2");
  verlet->find_pairs(in, out);
  const SearchVisit v = verlet->visit(0, in);
  EXPECT_EQ(v.kind, SearchVisit::Kind::list);
  ASSERT_EQ(v.grids.size(), 1u) << "the builder's cells of the last rebuild";
  EXPECT_EQ(v.grids[0].label, "builder m2, last rebuild");
  EXPECT_EQ(v.cells_visited, 0u);
}

}  // namespace
}  // namespace drumlab
