// The MPI domain decomposition on paper (engine/parallel/): RCB owns every particle once, splits
// counts (or weights) in proportion to the ranks on each side, cuts the longest side (along z for
// a deep drum, across it for a shallow one); the ghost layer equals a brute-force oracle, with
// periodic ends; `drumlab decompose` refuses bad rank counts with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "engine/contact/contact_model.hpp"
#include "engine/fill/file_fill.hpp"
#include "engine/parallel/exchange_cost.hpp"
#include "engine/parallel/ghost_layer.hpp"
#include "engine/parallel/rcb.hpp"
#include "engine/scene/scene_config.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab {
namespace {

/// n points uniform in the cylinder of diameter D along z over [0, depth).
std::vector<Vec3> cylinder_points(std::size_t n, double diameter, double depth,
                                  std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> p;
  const double r = 0.5 * diameter;
  while (p.size() < n) {
    const double x = (2.0 * u(rng) - 1.0) * r, y = (2.0 * u(rng) - 1.0) * r;
    if (x * x + y * y < r * r) p.emplace_back(x, y, u(rng) * depth);
  }
  return p;
}

/// The oracle's distance from x to the box, written without engine/periodic.hpp: the smallest
/// over the images z - H, z, z + H (H = period) when periodic.
double oracle_distance(const Box& b, const Vec3& x, double period) {
  auto gap = [](double lo, double hi, double v) { return std::max({0.0, lo - v, v - hi}); };
  const double gx = gap(b.lo.x(), b.hi.x(), x.x()), gy = gap(b.lo.y(), b.hi.y(), x.y());
  double gz = gap(b.lo.z(), b.hi.z(), x.z());
  if (period > 0.0) {
    gz = std::min(
        {gz, gap(b.lo.z(), b.hi.z(), x.z() - period), gap(b.lo.z(), b.hi.z(), x.z() + period)});
  }
  return std::sqrt(gx * gx + gy * gy + gz * gz);
}

TEST(Decomposition, EveryParticleIsOwnedOnceInsideItsBox) {
  const auto p = cylinder_points(5000, 0.9, 0.3, 1);
  const Box domain = drum_domain(0.9, 0.3);
  for (const int ranks : {1, 2, 3, 5, 7, 8, 13, 64}) {
    SCOPED_TRACE(ranks);
    const Decomposition d = rcb_decompose(p, {}, domain, ranks);
    ASSERT_EQ(d.ranks(), ranks);
    ASSERT_EQ(d.owner.size(), p.size());
    std::vector<std::size_t> count(static_cast<std::size_t>(ranks), 0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int r = d.owner[i];
      ASSERT_GE(r, 0);
      ASSERT_LT(r, ranks);
      ++count[static_cast<std::size_t>(r)];
      const Box& b = d.boxes[static_cast<std::size_t>(r)];
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(p[i][k], b.lo[k]);
        EXPECT_LE(p[i][k], b.hi[k]);
      }
    }
    EXPECT_EQ(count, d.owned);
    // The boxes tile the domain: their volumes add up to it.
    double volume = 0.0;
    for (const Box& b : d.boxes) volume += (b.hi - b.lo).prod();
    EXPECT_NEAR(volume, (domain.hi - domain.lo).prod(), 1e-12);
    EXPECT_EQ(static_cast<int>(d.nodes.size()), 2 * ranks - 1);
  }
}

TEST(Decomposition, EqualWeightsSplitWithinOneParticle) {
  const auto p = cylinder_points(10007, 0.9, 0.15, 2);
  for (const int ranks : {2, 3, 6, 10, 31, 100}) {
    SCOPED_TRACE(ranks);
    const Decomposition d = rcb_decompose(p, {}, drum_domain(0.9, 0.15), ranks);
    for (const RcbNode& node : d.nodes) {
      if (node.leaf()) continue;
      const RcbNode& left = d.nodes[static_cast<std::size_t>(node.left)];
      const RcbNode& right = d.nodes[static_cast<std::size_t>(node.right)];
      const int n = node.rank_end - node.rank_begin;
      const double target = static_cast<double>(node.count) * (left.rank_end - left.rank_begin) / n;
      EXPECT_LE(std::abs(static_cast<double>(left.count) - target), 1.0);
      EXPECT_EQ(left.count + right.count, node.count);
    }
    const auto [lo, hi] = std::minmax_element(d.owned.begin(), d.owned.end());
    // Within one particle per level of the tree.
    EXPECT_LE(*hi - *lo, static_cast<std::size_t>(std::ceil(std::log2(ranks))) + 1);
  }
}

TEST(Decomposition, WeightsSplitTheWorkNotTheCount) {
  // Particles with z < 0.1 weigh 9, the others 1: the weight, not the count, is halved.
  const auto p = cylinder_points(8000, 0.3, 1.0, 3);
  std::vector<double> w(p.size());
  double heavy = 0.0, total = 0.0, max_w = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    w[i] = p[i].z() < 0.1 ? 9.0 : 1.0;
    total += w[i];
    max_w = std::max(max_w, w[i]);
    if (p[i].z() < 0.1) heavy += w[i];
  }
  const Decomposition d = rcb_decompose(p, w, drum_domain(0.3, 1.0), 4);
  for (const RcbNode& node : d.nodes) {
    if (node.leaf()) continue;
    const RcbNode& left = d.nodes[static_cast<std::size_t>(node.left)];
    const double target =
        node.weight * (left.rank_end - left.rank_begin) / (node.rank_end - node.rank_begin);
    EXPECT_LE(std::abs(left.weight - target), max_w);
  }
  for (const double rw : d.owned_weight) EXPECT_NEAR(rw, total / 4, 2 * max_w);
  // The heavy slab holds ~half the weight: rank 0's box ends well below z = 0.5 of a count split.
  EXPECT_LT(d.boxes[0].hi.z(), 0.15);
  EXPECT_GT(heavy, 0.4 * total);
}

TEST(Decomposition, CutsAlongTheAxisOfADeepDrumAndAcrossAShallowOne) {
  {
    const auto p = cylinder_points(4000, 0.3, 1.2, 4);  // deep: H = 4 D
    const Decomposition d = rcb_decompose(p, {}, drum_domain(0.3, 1.2), 4);
    EXPECT_EQ(d.nodes[0].axis, 2);
    for (const RcbNode& node : d.nodes)
      if (!node.leaf()) {
        EXPECT_EQ(node.axis, 2);  // slabs 0.3 long and 0.3 wide at the end
      }
  }
  {
    // The demo drum's real fill (H = D / 6).
    const SceneConfig scene =
        load_scene(std::filesystem::path(DRUMLAB_SCENES_DIR) / "drum_demo.toml");
    const Particles fill = initial_fill(scene);
    const Decomposition d =
        rcb_decompose(fill.position, {}, drum_domain(scene.drum.diameter, scene.drum.depth), 8);
    for (const RcbNode& node : d.nodes)
      if (!node.leaf()) {
        EXPECT_NE(node.axis, 2);
      }
  }
}

void expect_ghosts_match_the_oracle(bool periodic) {
  const double depth = 0.4;
  const auto p = cylinder_points(3000, 0.5, depth, periodic ? 5 : 6);
  const std::optional<double> period =
      periodic ? std::optional<double>(depth) : std::optional<double>();
  // Three sizes: a particle's reach is its radius + 0.03 m, 0.035 to 0.045 m.
  const GhostReach reach{0.03, 0.015};
  std::vector<double> radius(p.size());
  for (std::size_t j = 0; j < p.size(); ++j) radius[j] = 0.005 * static_cast<double>(1 + j % 3);
  for (const int ranks : {2, 3, 5, 8, 12}) {
    SCOPED_TRACE(ranks);
    const Decomposition d = rcb_decompose(p, {}, drum_domain(0.5, depth), ranks);
    const GhostLayer g = ghost_layer(d, p, radius, reach, period);
    std::size_t wrapped = 0;
    for (int r = 0; r < ranks; ++r) {
      const Box& b = d.boxes[static_cast<std::size_t>(r)];
      std::vector<Index> expected;
      std::set<int> sources;
      for (std::size_t j = 0; j < p.size(); ++j) {
        if (d.owner[j] == r) continue;
        const double reach_j = 0.03 + radius[j];
        if (oracle_distance(b, p[j], periodic ? depth : 0.0) <= reach_j) {
          expected.push_back(static_cast<Index>(j));
          sources.insert(d.owner[j]);
          if (oracle_distance(b, p[j], 0.0) > reach_j) ++wrapped;
        }
      }
      EXPECT_EQ(g.ghosts[static_cast<std::size_t>(r)], expected) << "rank " << r;
      EXPECT_EQ(g.sources[static_cast<std::size_t>(r)],
                std::vector<int>(sources.begin(), sources.end()));
    }
    // Cuts along z exist at 5+ ranks here: some ghosts reach across the periodic ends.
    if (periodic && ranks >= 5) {
      EXPECT_GT(wrapped, 0u);
    }
  }
}

TEST(Decomposition, GhostsEqualTheBruteForceOracle) {
  expect_ghosts_match_the_oracle(false);
}

TEST(Decomposition, GhostsEqualTheBruteForceOracleWithPeriodicEnds) {
  expect_ghosts_match_the_oracle(true);
}

TEST(Decomposition, OneRankHasNoGhosts) {
  const auto p = cylinder_points(2000, 0.5, 0.4, 7);
  for (const bool periodic : {false, true}) {
    const Decomposition d = rcb_decompose(p, {}, drum_domain(0.5, 0.4), 1);
    const std::vector<double> radius(p.size(), 0.01);
    const GhostLayer g = ghost_layer(d, p, radius, GhostReach{0.09, 0.01},
                                     periodic ? std::optional<double>(0.4) : std::nullopt);
    ASSERT_EQ(g.ghosts.size(), 1u);
    EXPECT_TRUE(g.ghosts[0].empty());
    EXPECT_TRUE(g.sources[0].empty());
    const DecompositionCost c = decomposition_cost(d, g, 1e6, NetworkModel{});
    EXPECT_EQ(c.step_comm, 0.0);
    EXPECT_DOUBLE_EQ(c.speedup(), 1.0);
  }
}

TEST(Decomposition, ExchangeCostFollowsTheGhostsAndTheNetwork) {
  const auto p = cylinder_points(4000, 0.5, 0.4, 8);
  const Decomposition d = rcb_decompose(p, {}, drum_domain(0.5, 0.4), 4);
  const GhostLayer g =
      ghost_layer(d, p, std::vector<double>(p.size(), 0.01), GhostReach{0.02, 0.01}, std::nullopt);
  const NetworkModel net{1e9, 5e-6};
  const DecompositionCost c = decomposition_cost(d, g, 2e6, net);
  for (std::size_t r = 0; r < 4; ++r) {
    const RankCost& rc = c.ranks[r];
    EXPECT_EQ(rc.bytes, static_cast<double>(g.ghosts[r].size() * 72));
    EXPECT_DOUBLE_EQ(rc.comm, static_cast<double>(g.sources[r].size()) * 5e-6 + rc.bytes / 1e9);
    EXPECT_DOUBLE_EQ(rc.compute, static_cast<double>(d.owned[r]) / 2e6);
  }
  EXPECT_DOUBLE_EQ(c.step_serial, 4000 / 2e6);
  // Measured work per rank instead of the balanced count: rank 3 does half of it.
  const std::vector<double> work = {1.0, 1.0, 1.0, 3.0};
  const DecompositionCost w = decomposition_cost(d, g, 2e6, net, work);
  EXPECT_DOUBLE_EQ(w.ranks[3].compute, 0.5 * w.step_serial);
  EXPECT_DOUBLE_EQ(w.step_compute, 0.5 * w.step_serial);
}

// The pairs across boundaries against a brute-force count, and their cost: a rank computes half
// of its pairs across again (its neighbour's share), at a whole step's time over all pairs.
TEST(Decomposition, PairsAcrossAreCountedAndComputedOnBothSides) {
  const auto p = cylinder_points(2000, 0.5, 0.4, 9);
  const Decomposition d = rcb_decompose(p, {}, drum_domain(0.5, 0.4), 3);
  // A CSR list: each point with the later points (up to 200 on) within 0.05 m.
  std::vector<std::size_t> row = {0};
  std::vector<Index> col;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size() && j <= i + 200; ++j) {
      if ((p[i] - p[j]).norm() < 0.05) col.push_back(static_cast<Index>(j));
    }
    row.push_back(col.size());
  }
  const PairsAcross a = pairs_across(d, row, col);
  EXPECT_EQ(a.total, col.size());
  std::vector<std::size_t> expected(3, 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      for (int r = 0; r < 3; ++r) {
        expected[static_cast<std::size_t>(r)] +=
            (d.owner[i] == r) != (d.owner[col[k]] == r) ? 1 : 0;
      }
    }
  }
  EXPECT_EQ(a.across, expected);
  std::size_t sum = 0;
  for (const std::size_t n : a.across) sum += n;
  ASSERT_GT(sum, 0u);

  const GhostLayer g =
      ghost_layer(d, p, std::vector<double>(p.size(), 0.01), GhostReach{0.02, 0.01}, std::nullopt);
  const DecompositionCost plain = decomposition_cost(d, g, 1e6, NetworkModel{});
  const DecompositionCost with = decomposition_cost(d, g, 1e6, NetworkModel{}, {}, &a);
  for (std::size_t r = 0; r < 3; ++r) {
    EXPECT_DOUBLE_EQ(with.ranks[r].compute,
                     plain.ranks[r].compute + 0.5 * static_cast<double>(expected[r]) /
                                                  static_cast<double>(a.total) * plain.step_serial);
  }
  // Every pair across is one pair computed twice.
  EXPECT_NEAR(with.duplicated, 0.5 * static_cast<double>(sum) / static_cast<double>(a.total),
              1e-15);
  EXPECT_LT(with.speedup(), plain.speedup());
}

// A ghost of radius r must be seen within r + r_max + pair range + tolerance (+ the Verlet skin)
// of a box: the largest reach is 2 r_max + ..., a small particle's shorter by r_max - r.
TEST(Decomposition, ReachIsTheGhostsRadiusPlusTheLargestRadiusPlusPairRangePlusSkin) {
  SceneConfig scene = load_scene(std::filesystem::path(DRUMLAB_SCENES_DIR) / "drum_demo.toml");
  scene.search_method = "m5";
  const double range = ContactModel(scene).max_pair_range();
  EXPECT_DOUBLE_EQ(ghost_reach(scene).largest(), 2.0 * 0.015 + range + kTouchTolerance);
  EXPECT_DOUBLE_EQ(ghost_reach(scene).of(0.005), 0.005 + 0.015 + range + kTouchTolerance);
  scene.search_method = "verlet:m2";
  EXPECT_DOUBLE_EQ(ghost_reach(scene).largest(),
                   2.0 * 0.015 + range + kTouchTolerance + scene.performance.verlet_skin * 0.005);
  scene.liquid.enabled = true;  // rupture distance (1 + 0/2) V^(1/3) = 1 mm
  scene.liquid.surface_tension = scene.liquid.wall_surface_tension = 0.072;
  scene.liquid.bridge_volume = 1e-9;
  EXPECT_NEAR(ghost_reach(scene).largest() - (2.0 * 0.015 + scene.performance.verlet_skin * 0.005),
              1e-3 + kTouchTolerance, 1e-12);
}

TEST(Decomposition, BadRankCountsAreRefused) {
  EXPECT_THROW(rcb_decompose(std::vector<Vec3>{}, {}, Box{}, 0), InputError);
  // The CLI: one line naming --ranks, exit 2, before any fill.
  test::TempDir dir("decompose-ranks");
  const auto scene = dir.write("small.toml", test::small_drum_scene());
  for (const char* bad : {"0", "-2", "abc", "4,x", "1.5", "2,2000000"}) {
    SCOPED_TRACE(bad);
    const auto r =
        test::run_cli(fmt::format("decompose {} --ranks={} --no-settle", scene.string(), bad));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--ranks"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

TEST(Decomposition, CliPrintsOneRowPerRankCount) {
  test::TempDir dir("decompose-cli");
  const auto scene = dir.write("small.toml", test::small_drum_scene());
  const auto r = test::run_cli(fmt::format(
      "decompose {} --ranks 1,2,3 --no-settle --rate 1e6 --weight pairs", scene.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* row : {"\n     1 ", "\n     2 ", "\n     3 "})
    EXPECT_NE(r.output.find(row), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("72 B per ghost"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace drumlab
