// The phases of granulation read off a size curve (engine/analysis/growth_phases.hpp): on
// constructed curves the phases start and end where the documented thresholds put them; a curve
// without granules or without growth shows only what it has.
#include <gtest/gtest.h>

#include "engine/analysis/growth_phases.hpp"

namespace drumlab::test {
namespace {

std::vector<AgglomerateStats> curve(const std::vector<std::size_t>& count,
                                    const std::vector<double>& d50) {
  std::vector<AgglomerateStats> rows(count.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    rows[k].time = 0.1 * static_cast<double>(k);
    rows[k].count = count[k];
    rows[k].d50 = d50[k];
  }
  return rows;
}

TEST(GrowthPhases, NucleationGrowthAndConsolidationWhereTheThresholdsPutThem) {
  // Frames 0-1 dry; nuclei appear (count to 100 at frame 5), then merge while d50 rises from 1 to
  // 3 mm (90 % of the rise, 2.8 mm, at frame 9), then d50 creeps.
  const auto rows = curve({0, 0, 10, 40, 80, 100, 95, 80, 60, 50, 48, 47, 47},
                          {1.0, 1.0, 1.0, 1.0, 1.05, 1.1, 1.4, 1.9, 2.5, 2.85, 2.9, 2.95, 3.0});
  const std::vector<GrowthPhase> p = growth_phases(rows);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].name, "nucleation");
  EXPECT_EQ(p[0].first, 2u);  // the first granule
  EXPECT_EQ(p[0].last, 5u);   // count first >= 90 of 100
  EXPECT_EQ(p[1].name, "growth");
  EXPECT_EQ(p[1].first, 5u);
  EXPECT_EQ(p[1].last, 9u);  // d50 first >= 1 + 0.9 * 2
  EXPECT_EQ(p[2].name, "consolidation");
  EXPECT_EQ(p[2].first, 9u);
  EXPECT_EQ(p[2].last, 12u);
}

TEST(GrowthPhases, ACurveShowsOnlyThePhasesItHas) {
  EXPECT_TRUE(growth_phases(curve({0, 0, 0}, {1.0, 1.0, 1.0})).empty());
  // Granules that never grow: nucleation only.
  const auto flat = growth_phases(curve({0, 5, 10, 10}, {1.0, 1.0, 1.0, 1.0}));
  ASSERT_EQ(flat.size(), 1u);
  EXPECT_EQ(flat[0].name, "nucleation");
  EXPECT_EQ(flat[0].last, 2u);
  // Growth to the last frame: no consolidation.
  const auto growing = growth_phases(curve({1, 10, 10, 10}, {1.0, 1.0, 1.5, 2.0}));
  ASSERT_EQ(growing.size(), 2u);
  EXPECT_EQ(growing[1].name, "growth");
  EXPECT_EQ(growing[1].last, 3u);
}

}  // namespace
}  // namespace drumlab::test
