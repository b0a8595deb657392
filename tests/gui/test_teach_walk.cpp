// The teaching mode's walk through one particle's search (app/gui/teach_steps): the cells in the
// method's order, candidates revealed with the cell they lie in, the whole search at the end.
#include <gtest/gtest.h>

#include "app/gui/teach_steps.hpp"
#include "engine/session/frame_snapshot.hpp"
#include "engine/session/run_session.hpp"
#include "tests/small_drum_text.hpp"

namespace drumlab::test {
namespace {

std::unique_ptr<Simulation> settled_small_drum() {
  SmallDrumText t;
  SessionOptions o;
  o.settle_time = 0.1;
  RunSession session(parse_scene(t.text(), "small drum"), o);
  session.settle();
  return session.release_simulation();
}

TEST(TeachWalk, RevealsTheWholeSearchCellByCell) {
  const auto sim = settled_small_drum();
  SnapshotRequest req;
  req.focus_id = 0;
  req.compare_methods = {"m1", "m2", "m3", "m4", "m5"};
  const FrameSnapshot s = take_snapshot(*sim, req);
  ASSERT_EQ(s.compare_visits.size(), 5u);
  for (const MethodVisit& m : s.compare_visits) {
    SCOPED_TRACE(m.method);
    const gui::TeachWalk walk(m.visit, s.position);
    ASSERT_EQ(walk.steps(), m.visit.grids.front().count());
    EXPECT_EQ(walk.counts(0).candidates, 0u);
    EXPECT_FALSE(walk.prefix(0).grids.front().has_own);
    gui::TeachCounts last{};
    for (std::size_t k = 1; k < walk.steps(); ++k) {
      const gui::TeachCounts c = walk.counts(k);
      EXPECT_EQ(c.cells, k);
      EXPECT_EQ(walk.prefix(k).grids.front().count(), k);
      EXPECT_GE(c.candidates, last.candidates);
      EXPECT_GE(c.contacts, last.contacts);
      last = c;
    }
    const SearchVisit whole = walk.prefix(walk.steps());
    EXPECT_EQ(whole.candidates, m.visit.candidates);
    EXPECT_EQ(whole.contacts, m.visit.contacts);
    EXPECT_EQ(walk.counts(walk.steps()).cells, m.visit.cells_visited);
  }
}

TEST(FrameSnapshot, CopiesTheStateAndReplaysTheFocusSearch) {
  const auto sim = settled_small_drum();
  SnapshotRequest req;
  req.focus_id = 7;
  req.compare_methods = {"brute"};
  const FrameSnapshot s = take_snapshot(*sim, req);
  const Particles& p = sim->particles();
  EXPECT_EQ(s.position, p.position);
  EXPECT_EQ(s.radius, p.radius);
  EXPECT_EQ(s.id, p.id);
  EXPECT_EQ(s.steps, sim->steps());
  EXPECT_EQ(s.search_name, std::string(sim->search().name()));
  ASSERT_TRUE(s.grid.has_value()) << "m5 has a cell grid";
  ASSERT_TRUE(s.focus_index.has_value());
  EXPECT_EQ(p.id[*s.focus_index], 7u);
  const SearchVisit v = sim->search().visit(*s.focus_index, sim->search_input());
  ASSERT_TRUE(s.focus_visit.has_value());
  EXPECT_EQ(s.focus_visit->candidates, v.candidates);
  EXPECT_EQ(s.focus_visit->contacts, v.contacts);
  // Per size class: every particle counted once, the counters summing to the step's.
  std::size_t n = 0;
  std::uint64_t tests = 0;
  for (const ClassCounters& c : s.per_class) {
    n += c.particles;
    tests += c.pairs_tested;
  }
  EXPECT_EQ(n, p.size());
  EXPECT_EQ(tests, s.counters.pairs_tested);
  ASSERT_TRUE(s.diagnostics.has_value());
  // A focus id the simulation lacks gives no visit (the renderer reports the bad id).
  req.focus_id = 100000;
  EXPECT_FALSE(take_snapshot(*sim, req).focus_visit.has_value());
}

}  // namespace
}  // namespace drumlab::test
