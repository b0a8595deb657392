// The messages of an MPI run's start (engine/parallel/start_message.hpp): the header read back
// equals what was packed (scalars, extra arrays' layout, the cut tree), and the parts of all ranks
// of a state cut by RCB (records packed and read back) hold every particle once as owned, each
// rank's ghosts (by owner, as ghost_layer lists them) with all their arrays, and exactly the
// contact records of the pairs both of whose particles the rank holds.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>
#include <vector>

#include "engine/parallel/start_message.hpp"

namespace drumlab {
namespace {

/// 300 particles in a box with a film array, wall history and a contact list of near pairs.
SimulationState a_state() {
  SimulationState s;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Particles& p = s.particles;
  for (int k = 0; k < 300; ++k) {
    p.add(Vec3(-0.1 + 0.2 * u(rng), -0.1 + 0.2 * u(rng), 0.3 * u(rng)), 0.004 + 0.002 * u(rng),
          2500.0, 0);
    p.velocity.back() = Vec3(u(rng), u(rng), u(rng));
  }
  p.add_array("film", 0.25);
  for (std::size_t i = 0; i < p.size(); ++i) p.extra[0].values[i] = double(i);
  s.wall_history.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) s.wall_history[i][1] = Vec3(double(i), 0.0, 1.0);
  s.time = 0.125;
  s.dt = 1e-5;
  s.drum_omega = 2.5;
  s.drum_angle = 0.75;
  s.steps = 12500;
  s.search_method = "verlet:m2";
  s.contact_state_size = 1;
  s.contact_row_start.push_back(0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      if ((p.position[i] - p.position[j]).norm() > 0.04) continue;
      s.contact_col.push_back(static_cast<Index>(j));
      s.contact_history.push_back(Vec3(double(i), double(j), 0.0));
      s.contact_state.push_back(double(i * 1000 + j));
    }
    s.contact_row_start.push_back(s.contact_col.size());
  }
  return s;
}

TEST(StartMessage, TheHeaderReadsBackAsPacked) {
  const SimulationState s = a_state();
  const Decomposition d = rcb_decompose(s.particles.position, {}, drum_domain(0.2, 0.3), 3);
  const StartHeader h = unpack_start_header(pack_start_header(s, d));
  EXPECT_EQ(h.state.time, s.time);
  EXPECT_EQ(h.state.dt, s.dt);
  EXPECT_EQ(h.state.drum_omega, s.drum_omega);
  EXPECT_EQ(h.state.drum_angle, s.drum_angle);
  EXPECT_EQ(h.state.steps, s.steps);
  EXPECT_EQ(h.state.search_method, s.search_method);
  EXPECT_EQ(h.state.contact_state_size, 1u);
  EXPECT_EQ(h.state.particles.size(), 0u);
  ASSERT_EQ(h.state.particles.extra.size(), 1u);
  EXPECT_EQ(h.state.particles.extra[0].name, "film");
  EXPECT_EQ(h.state.particles.extra[0].initial, 0.25);
  EXPECT_EQ(h.particles, 300u);
  EXPECT_EQ(h.max_radius, s.particles.max_radius());
  ASSERT_EQ(h.decomposition.nodes.size(), d.nodes.size());
  for (std::size_t k = 0; k < d.nodes.size(); ++k) {
    EXPECT_EQ(h.decomposition.nodes[k].cut, d.nodes[k].cut);
    EXPECT_EQ(h.decomposition.nodes[k].axis, d.nodes[k].axis);
    EXPECT_EQ(h.decomposition.nodes[k].left, d.nodes[k].left);
    EXPECT_EQ(h.decomposition.nodes[k].box.hi, d.nodes[k].box.hi);
    EXPECT_EQ(h.decomposition.nodes[k].rank_end, d.nodes[k].rank_end);
  }
  ASSERT_EQ(h.decomposition.boxes.size(), 3u);
  EXPECT_EQ(h.decomposition.owned, d.owned);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(h.decomposition.boxes[r].lo, d.boxes[r].lo);
  // Owners follow from the tree alone.
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    EXPECT_EQ(rcb_owner(h.decomposition, s.particles.position[i]), d.owner[i]);
  }
}

TEST(StartMessage, PartsHoldEveryParticleOnceTheGhostsAndThePairsHeld) {
  const SimulationState s = a_state();
  const Particles& p = s.particles;
  const int ranks = 3;
  const Decomposition d = rcb_decompose(p.position, {}, drum_domain(0.2, 0.3), ranks);
  const GhostLayer g = ghost_layer(d, p.position, p.radius, GhostReach{0.024, 0.006}, std::nullopt);
  std::vector<std::uint8_t> held(p.size(), 0);
  std::vector<int> owned_by(p.size(), -1);
  const std::size_t size = packed_size(p);
  for (int q = 0; q < ranks; ++q) {
    StartPart part = start_part(s, d, g, q, held);
    part.records = unpack_records(pack_records(part.records));  // as sent
    EXPECT_EQ(held, std::vector<std::uint8_t>(p.size(), 0)) << "scratch left as found";
    std::set<std::uint64_t> here;
    // Owned: every array as in the state, ascending slots.
    Particles owned = empty_like(p);
    WallHistory wall;
    std::size_t pos = 0;
    std::uint64_t last = 0;
    for (std::size_t k = 0; k < part.owned_count; ++k) {
      const std::uint64_t slot = unpack_particle(part.owned, pos, owned, wall);
      EXPECT_TRUE(k == 0 || slot > last);
      last = slot;
      EXPECT_EQ(owned_by[slot], -1) << "particle " << slot << " owned twice";
      owned_by[slot] = q;
      EXPECT_EQ(d.owner[slot], q);
      EXPECT_EQ(owned.position[k], p.position[slot]);
      EXPECT_EQ(owned.velocity[k], p.velocity[slot]);
      EXPECT_EQ(owned.extra[0].values[k], double(slot));
      EXPECT_EQ(wall[k], s.wall_history[slot]);
      here.insert(slot);
    }
    EXPECT_EQ(pos, part.owned.size());
    // Ghosts, by owner: together the ghost layer's list.
    ASSERT_EQ(part.ghosts.size(), 3u);
    std::vector<std::uint64_t> ghosts;
    for (std::size_t r = 0; r < part.ghosts.size(); ++r) {
      Particles gp = empty_like(p);
      WallHistory gw;
      for (std::size_t at = 0; at < part.ghosts[r].size();) {
        const std::uint64_t slot = unpack_particle(part.ghosts[r], at, gp, gw);
        EXPECT_EQ(d.owner[slot], static_cast<int>(r));
        EXPECT_EQ(gp.position.back(), p.position[slot]);
        EXPECT_EQ(gp.extra[0].values.back(), double(slot));
        ghosts.push_back(slot);
        here.insert(slot);
      }
      EXPECT_EQ(part.ghosts[r].size() % size, 0u);
    }
    std::sort(ghosts.begin(), ghosts.end());
    const std::vector<std::uint64_t> listed(g.ghosts[q].begin(), g.ghosts[q].end());
    EXPECT_EQ(ghosts, listed);
    EXPECT_FALSE(ghosts.empty());
    // Records: exactly the pairs with both particles here, each with its history and state.
    std::set<std::pair<std::uint64_t, std::uint64_t>> expected, got;
    for (std::size_t i = 0; i + 1 < s.contact_row_start.size(); ++i) {
      for (std::size_t k = s.contact_row_start[i]; k < s.contact_row_start[i + 1]; ++k) {
        const std::uint64_t j = s.contact_col[k];
        if (here.count(i) != 0 && here.count(j) != 0) expected.insert({i, j});
      }
    }
    ASSERT_EQ(part.records.state_size, 1u);
    for (std::size_t k = 0; k < part.records.size(); ++k) {
      const auto a = part.records.a[k], b = part.records.b[k];
      got.insert({a, b});
      EXPECT_EQ(part.records.history[k], Vec3(double(a), double(b), 0.0));
      EXPECT_EQ(part.records.state[k], double(a * 1000 + b));
    }
    EXPECT_EQ(got, expected);
    EXPECT_LT(got.size(), s.contact_col.size());
  }
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_GE(owned_by[i], 0) << "particle " << i;
}

}  // namespace
}  // namespace drumlab
