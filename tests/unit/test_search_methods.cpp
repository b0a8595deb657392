// One suite over every contact-search method, each checked against the brute-force oracle: the
// same pair set, every pair once, on inputs chosen to break grids (size ratios 1, 3, 10, centres on
// cell faces, negative and far-from-origin coordinates, deep columns, dense clusters, periodic z,
// a Verlet margin, sparse inputs that force the hashed cell index, size distributions).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "engine/scene/size_distribution.hpp"
#include "engine/search/cell_grid.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/half_stencil.hpp"
#include "engine/search/search_input.hpp"
#include "engine/threads.hpp"

namespace drumlab {
namespace {

struct Cloud {
  std::vector<Vec3> x;
  std::vector<double> r;
};

/// Random spheres in a box; radii drawn from {r0, ratio*r0, (1+ratio)/2*r0}.
Cloud random_box(std::size_t n, double ratio, const Vec3& lo, const Vec3& size, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double r0 = 0.005;
  const double radii[3] = {r0, 0.5 * (1.0 + ratio) * r0, ratio * r0};
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.x.push_back(lo + Vec3(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z()));
    c.r.push_back(radii[i % 3]);
  }
  return c;
}

std::vector<IndexPair> sorted_pairs(ContactSearch& s, const Cloud& c, double margin = 0.0,
                                    std::optional<double> period = std::nullopt,
                                    std::optional<Box> domain = std::nullopt) {
  SearchInput in{c.x, c.r, margin, domain, period};
  std::vector<IndexPair> out;
  s.find_pairs(in, out);
  std::sort(out.begin(), out.end());
  return out;
}

/// A fresh `method`'s pairs of `in` on `threads` threads; the search, for its counters.
std::unique_ptr<ContactSearch> find_on(int threads, const std::string& method,
                                       const SearchInput& in, std::vector<IndexPair>& out) {
  auto search = make_search(method);
  const int saved = max_threads();
  set_thread_count(threads);
  search->find_pairs(in, out);
  set_thread_count(saved);
  return search;
}

class SearchMethod : public ::testing::TestWithParam<std::string> {
 protected:
  void expect_same_as_brute(const Cloud& c, double margin = 0.0,
                            std::optional<double> period = std::nullopt,
                            std::optional<Box> domain = std::nullopt) {
    auto oracle = make_search("brute");
    auto method = make_search(GetParam());
    const auto expected = sorted_pairs(*oracle, c, margin, period, domain);
    const auto got = sorted_pairs(*method, c, margin, period, domain);
    ASSERT_EQ(std::adjacent_find(got.begin(), got.end()), got.end()) << "a pair was found twice";
    EXPECT_EQ(got.size(), expected.size());
    EXPECT_EQ(got, expected);
    EXPECT_EQ(method->counters().pairs_found, got.size());
    EXPECT_GE(method->counters().pairs_tested, got.size());
  }
};

TEST_P(SearchMethod, RandomBoxSizeRatio1) {
  expect_same_as_brute(random_box(3000, 1.0, Vec3::Zero(), Vec3(0.3, 0.3, 0.15), 1));
}

TEST_P(SearchMethod, RandomBoxSizeRatio3) {
  expect_same_as_brute(random_box(3000, 3.0, Vec3::Zero(), Vec3(0.4, 0.3, 0.15), 2));
}

TEST_P(SearchMethod, RandomBoxSizeRatio10) {
  expect_same_as_brute(random_box(2000, 10.0, Vec3::Zero(), Vec3(0.6, 0.5, 0.3), 3));
}

TEST_P(SearchMethod, CentresOnCellFacesTouching) {
  // Simple cubic lattices of touching spheres whose centres sit on multiples of the cell side:
  // every neighbour is at exactly r_i + r_j, which must count as a contact.
  Cloud c;
  for (double r : {0.005, 0.010, 0.015}) {
    const double y0 = r == 0.005 ? 0.0 : (r == 0.010 ? 0.1 : 0.2);
    for (int iz = 0; iz < 4; ++iz)
      for (int iy = 0; iy < 4; ++iy)
        for (int ix = 0; ix < 12; ++ix) {
          c.x.emplace_back((2 * ix + 1) * r, y0 + (2 * iy + 1) * r, (2 * iz + 1) * r);
          c.r.push_back(r);
        }
  }
  expect_same_as_brute(c);
  // Also on the paper's fixed grid with origin (0, 0, 0).
  expect_same_as_brute(c, 0.0, std::nullopt, Box{Vec3::Zero(), Vec3(0.5, 0.5, 0.5)});
  auto brute = make_search("brute");
  EXPECT_GT(sorted_pairs(*brute, c).size(), 3 * 12 * 4 * 4u);  // the lattices really touch
}

TEST_P(SearchMethod, NegativeAndFarFromOriginCoordinates) {
  expect_same_as_brute(random_box(1500, 3.0, Vec3(-0.7, -0.2, -0.5), Vec3(0.3, 0.3, 0.2), 4));
  expect_same_as_brute(random_box(1500, 3.0, Vec3(1e5, -2e5, 3e4), Vec3(0.3, 0.3, 0.2), 5));
}

TEST_P(SearchMethod, DeepColumn) {
  expect_same_as_brute(random_box(3000, 3.0, Vec3::Zero(), Vec3(0.1, 0.1, 2.0), 6));
}

TEST_P(SearchMethod, DenseClusterInSparseCloud) {
  Cloud c = random_box(400, 3.0, Vec3::Zero(), Vec3(2.0, 2.0, 1.0), 7);
  const Cloud cluster = random_box(1500, 3.0, Vec3(1.0, 1.0, 0.5), Vec3(0.04, 0.04, 0.04), 8);
  c.x.insert(c.x.end(), cluster.x.begin(), cluster.x.end());
  c.r.insert(c.r.end(), cluster.r.begin(), cluster.r.end());
  expect_same_as_brute(c);
}

TEST_P(SearchMethod, FarApartParticlesUseSparseIndex) {
  Cloud c = random_box(300, 3.0, Vec3::Zero(), Vec3(0.1, 0.1, 0.1), 9);
  const Cloud far = random_box(300, 3.0, Vec3(5e3, 4e3, 3e3), Vec3(0.1, 0.1, 0.1), 10);
  c.x.insert(c.x.end(), far.x.begin(), far.x.end());
  c.r.insert(c.r.end(), far.r.begin(), far.r.end());
  expect_same_as_brute(c);
  auto method = make_search(GetParam());
  sorted_pairs(*method, c);
  if (auto* grid = dynamic_cast<CellGridSearch*>(method.get())) {
    EXPECT_TRUE(grid->geometry().hashed) << "a dense grid over this box would need ~1e16 cells";
  }
}

TEST_P(SearchMethod, PeriodicZ) {
  // Particles near both ends must pair across the periodic boundary (minimum image).
  Cloud c = random_box(3000, 3.0, Vec3::Zero(), Vec3(0.3, 0.3, 0.3), 11);
  expect_same_as_brute(c, 0.0, 0.3);
  Cloud thin = random_box(800, 3.0, Vec3::Zero(), Vec3(0.3, 0.3, 0.09), 12);
  expect_same_as_brute(thin, 0.0, 0.09);  // too thin for a 3D stencil: searched as one layer
}

TEST_P(SearchMethod, VerletMargin) {
  expect_same_as_brute(random_box(2000, 3.0, Vec3::Zero(), Vec3(0.3, 0.3, 0.15), 13), 0.004);
}

/// Random spheres in a box with radii drawn from a size distribution (a scene class's radii).
Cloud distribution_box(std::size_t n, const SizeDistribution& d, const Vec3& size, unsigned seed) {
  Cloud c = random_box(n, 1.0, Vec3::Zero(), size, seed);
  std::mt19937_64 rng(seed);
  for (double& r : c.r) r = d.draw(rng);
  return c;
}

TEST_P(SearchMethod, SizeDistributions) {
  // Continuous radii (no two alike: a per-size stencil per particle, factor-of-2 levels) and a
  // table; then a margin as a liquid bridge's rupture distance or a Verlet skin makes it, and
  // periodic ends (the MercuryDPM drum's).
  const SizeDistribution normal = SizeDistribution::normal(0.005, 0.0005, 3.0);
  // r_max / r_min = 6.1: three factor-of-2 levels (a wider one makes m3's per-size stencils slow)
  const SizeDistribution wide = SizeDistribution::lognormal(0.004, 0.0015, 2.5);
  const SizeDistribution table = SizeDistribution::table({0.003, 0.004, 0.009}, {5.0, 3.0, 1.0});
  expect_same_as_brute(distribution_box(3000, normal, Vec3(0.3, 0.3, 0.15), 21));
  expect_same_as_brute(distribution_box(2000, wide, Vec3(0.2, 0.15, 0.1), 22));
  expect_same_as_brute(distribution_box(2000, table, Vec3(0.3, 0.3, 0.15), 23));
  expect_same_as_brute(distribution_box(2000, normal, Vec3(0.3, 0.3, 0.15), 24), 0.0015);
  expect_same_as_brute(distribution_box(2000, wide, Vec3(0.2, 0.15, 0.1), 25), 0.002, 0.1);
  auto brute = make_search("brute");
  EXPECT_GT(sorted_pairs(*brute, distribution_box(2000, wide, Vec3(0.2, 0.15, 0.1), 22)).size(),
            1000u);  // dense enough that many pairs touch
}

TEST_P(SearchMethod, TinyInputs) {
  expect_same_as_brute(Cloud{});
  expect_same_as_brute(Cloud{{Vec3(1, 2, 3)}, {0.01}});
  expect_same_as_brute(Cloud{{Vec3(0, 0, 0), Vec3(0.02, 0, 0)}, {0.01, 0.01}});
  expect_same_as_brute(Cloud{{Vec3(0, 0, 0), Vec3(0, 0, 0)}, {0.01, 0.01}});  // coincident
}

TEST_P(SearchMethod, SameOutputAndCountersForOneAndTwoThreads) {
  // Size ratio 3 (several mlgrid levels), a Verlet margin: the pairs, in the same order, and every
  // counter must not depend on the thread count.
  const Cloud c = random_box(4000, 3.0, Vec3(0, 0, 0), Vec3(0.3, 0.3, 0.1), 21);
  const SearchInput in{c.x, c.r, 0.002, std::nullopt, std::nullopt};
  std::vector<IndexPair> one, two;
  const auto a = find_on(1, GetParam(), in, one);
  const auto b = find_on(2, GetParam(), in, two);
  EXPECT_EQ(one, two);
  EXPECT_EQ(a->counters().pairs_tested, b->counters().pairs_tested);
  EXPECT_EQ(a->counters().cells_visited, b->counters().cells_visited);
  EXPECT_TRUE(std::ranges::equal(a->pairs_tested_per_particle(), b->pairs_tested_per_particle()));
  EXPECT_TRUE(std::ranges::equal(a->cells_visited_per_particle(), b->cells_visited_per_particle()));
}

TEST_P(SearchMethod, RejectsBadInput) {
  auto method = make_search(GetParam());
  std::vector<IndexPair> out;
  Cloud nan{{Vec3(0, std::nan(""), 0)}, {0.01}};
  EXPECT_THROW(method->find_pairs(SearchInput{nan.x, nan.r, 0.0, std::nullopt, std::nullopt}, out),
               InputError);
  Cloud negative{{Vec3(0, 0, 0)}, {-0.01}};
  EXPECT_THROW(
      method->find_pairs(SearchInput{negative.x, negative.r, 0.0, std::nullopt, std::nullopt}, out),
      InputError);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, SearchMethod, ::testing::ValuesIn(search_method_names()),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), ':', '_');
                           return name;
                         });

TEST(HalfStencil, CellCountsMatchThePaper) {
  // The paper's stencil sizes for k = 4, 5, 6 (2D, cell = R_min) and k = 2 (cell = R_max).
  EXPECT_EQ(half_stencil_cells(4, false), 41u);
  EXPECT_EQ(half_stencil_cells(5, false), 61u);
  EXPECT_EQ(half_stencil_cells(6, false), 85u);
  EXPECT_EQ(half_stencil_cells(2, false), 13u);
  EXPECT_EQ(half_stencil_cells(2, true), 63u);  // true half shell (paper: 13 x 5 = 65)
  for (bool three_d : {false, true}) {
    const HalfStencil st(6, three_d);
    for (int k = 0; k <= 6; ++k) EXPECT_EQ(st.prefix_end[k] + 1, half_stencil_cells(k, three_d));
  }
}

TEST(CellGrid, InteriorParticleVisitsThePaperStencil) {
  // A small particle (r = R_min) with R_max = 3 R_min, far from the grid edges, in method 1
  // visits k = 4 -> 41 cells; a large one k = 6 -> 85.
  Cloud c;
  c.x = {Vec3(0.5, 0.5, 0.05), Vec3(0.3, 0.3, 0.05), Vec3(0.0, 0.0, 0.0), Vec3(1.0, 1.0, 0.1)};
  c.r = {0.005, 0.015, 0.005, 0.005};
  CellGridSearch m1(paper_method(1));
  sorted_pairs(m1, c);
  EXPECT_EQ(m1.reach_cells(0), 4);
  EXPECT_EQ(m1.reach_cells(1), 6);
  EXPECT_EQ(m1.cells_visited_per_particle()[0], 41u);
  EXPECT_EQ(m1.cells_visited_per_particle()[1], 85u);
}

TEST(MultiLevelGrid, OneSizeVisitsTheThreeByThreeHalfShell) {
  // One size class: cells as wide as the contact reach, so every particle visits at most the
  // 14 cells of the 3x3x3 half shell (an earlier version's round-off allowance made it 5x5x5).
  Cloud c = random_box(3000, 1.0, Vec3(-0.1, -0.1, 0.0), Vec3(0.2, 0.2, 0.1), 5);
  for (double& r : c.r) r = 0.005;
  auto ml = make_search("mlgrid");
  sorted_pairs(*ml, c);
  const auto cells = ml->cells_visited_per_particle();
  EXPECT_EQ(*std::max_element(cells.begin(), cells.end()), 14u);  // fewer only at the edges
}

TEST(MultiLevelGrid, LargeInputTheSameOnOneAndTwoThreads) {
  // Enough particles that the level assignment, binning and bounds run on two threads and the
  // counting sort by level in two shares; three radii (exact levels) and then twelve (log2
  // levels): the same pairs in the same order, the same counters.
  for (const std::size_t sizes : {3u, 12u}) {
    Cloud c = random_box(70000, 3.0, Vec3(-0.4, -0.2, 0.0), Vec3(0.8, 0.4, 0.3), 8);
    for (std::size_t i = 0; i < c.r.size(); ++i) {
      c.r[i] = 0.002 * (1.0 + static_cast<double>(i % sizes) / static_cast<double>(sizes));
    }
    const SearchInput in{c.x, c.r, 0.001, std::nullopt, std::nullopt};
    std::vector<IndexPair> one, two;
    const auto a = find_on(1, "mlgrid", in, one);
    const auto b = find_on(2, "mlgrid", in, two);
    ASSERT_FALSE(one.empty());
    EXPECT_EQ(one, two) << sizes << " radii";
    EXPECT_TRUE(std::ranges::equal(a->pairs_tested_per_particle(), b->pairs_tested_per_particle()));
    EXPECT_TRUE(
        std::ranges::equal(a->cells_visited_per_particle(), b->cells_visited_per_particle()));
  }
}

TEST(SearchInputCheck, NamesTheFirstBadParticleOnAnyTeam) {
  // Particles 5000 (a negative radius) and 9000 (a non-finite position) of 12000 are at fault: the
  // check runs on every thread, and it names the first whatever the team.
  Cloud c = random_box(12000, 1.0, Vec3(0, 0, 0), Vec3(1, 1, 1), 3);
  c.x[9000].y() = std::nan("");
  c.r[5000] = -0.01;
  const int saved = max_threads();
  for (const int threads : {1, 2}) {
    set_thread_count(threads);
    try {
      validate_search_input(SearchInput{c.x, c.r, 0.0, std::nullopt, std::nullopt});
      ADD_FAILURE() << "expected InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "search: particle 5000 has radius -0.01 (must be positive)");
    }
  }
  set_thread_count(saved);
}

TEST(SearchFactory, UnknownMethodNamesTheValidOnes) {
  try {
    make_search("m7");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m7"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("brute"), std::string::npos);
  }
}

}  // namespace
}  // namespace drumlab
