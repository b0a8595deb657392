// The community granule criterion (engine/analysis/granule_communities.hpp): igraph's Leiden
// partition of the force-weighted bond network against an independent oracle (the modularity of
// every partition of small networks, enumerated), its independence of storage and bond order, and
// the frame analysis on a percolating network of weak bridges around two strongly bound clusters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "engine/analysis/agglomerates.hpp"
#include "engine/analysis/granule_communities.hpp"

namespace drumlab::test {
namespace {

/// Modularity Q = 1/(2W) sum_ij [w_ij - gamma s_i s_j / (2W)] delta(c_i, c_j) of a partition.
double modularity(std::size_t n, const std::vector<Bond>& bonds, const std::vector<int>& part,
                  double gamma) {
  std::vector<double> s(n, 0.0);
  double w = 0.0, inside = 0.0;
  for (const Bond& b : bonds) {
    s[b.i] += b.force;
    s[b.j] += b.force;
    w += b.force;
    if (part[b.i] == part[b.j]) inside += 2.0 * b.force;  // w_ij and w_ji
  }
  std::map<int, double> strength_of;
  for (std::size_t i = 0; i < n; ++i) strength_of[part[i]] += s[i];
  double expected = 0.0;
  for (const auto& [c, sc] : strength_of) expected += gamma * sc * sc / (2.0 * w);
  return (inside - expected) / (2.0 * w);
}

/// The partition of largest modularity among all set partitions of n nodes (restricted growth
/// strings), as labels canonical by first appearance.
std::vector<int> best_partition(std::size_t n, const std::vector<Bond>& bonds, double gamma) {
  std::vector<int> a(n, 0), best(n, 0);
  double best_q = -1e300;
  const auto visit = [&](auto&& self, std::size_t k, int used) -> void {
    if (k == n) {
      const double q = modularity(n, bonds, a, gamma);
      if (q > best_q + 1e-12) {
        best_q = q;
        best = a;
      }
      return;
    }
    for (int c = 0; c <= used; ++c) {
      a[k] = c;
      self(self, k + 1, std::max(used, c + 1));
    }
  };
  a[0] = 0;
  visit(visit, 1, 1);
  return best;
}

/// Labels by first appearance, so that two partitions compare equal when they group alike.
std::vector<int> canonical(const std::vector<std::size_t>& root) {
  std::map<std::size_t, int> name;
  std::vector<int> out;
  for (const std::size_t r : root)
    out.push_back(name.try_emplace(r, int(name.size())).first->second);
  return out;
}

std::vector<std::uint32_t> ids(std::size_t n) {
  std::vector<std::uint32_t> id(n);
  std::iota(id.begin(), id.end(), 0u);
  return id;
}

/// Three groups of three particles, strongly bound inside (random forces in [1, 2] N) and weakly
/// between (a few random bonds of [0.05, 0.3] N), the groups' members interleaved in storage.
std::vector<Bond> planted_network(std::mt19937& rng) {
  std::uniform_real_distribution<double> strong(1.0, 2.0), weak(0.05, 0.3);
  const int group[9] = {0, 1, 2, 0, 1, 2, 0, 1, 2};
  std::vector<Bond> bonds;
  for (Index i = 0; i < 9; ++i) {
    for (Index j = i + 1; j < 9; ++j) {
      if (group[i] == group[j]) {
        bonds.push_back({i, j, 0.0, strong(rng), 0.0});
      } else if (rng() % 4 == 0) {
        bonds.push_back({i, j, 0.0, weak(rng), 0.0});
      }
    }
  }
  return bonds;
}

TEST(GranuleCommunities, LeidenFindsTheModularityOptimumOfSmallNetworks) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const std::vector<Bond> bonds = planted_network(rng);
    for (const double gamma : {1.0, 0.5}) {
      const std::vector<int> oracle = best_partition(9, bonds, gamma);
      const std::vector<int> leiden = canonical(bond_communities(ids(9), bonds, gamma));
      EXPECT_EQ(leiden, oracle) << "trial " << trial << ", resolution " << gamma;
      EXPECT_NEAR(modularity(9, bonds, leiden, gamma), modularity(9, bonds, oracle, gamma), 1e-12);
    }
  }
  // The planted groups at resolution 1: members 0, 3, 6 / 1, 4, 7 / 2, 5, 8.
  const std::vector<int> planted = {0, 1, 2, 0, 1, 2, 0, 1, 2};
  std::mt19937 again(7);
  EXPECT_EQ(canonical(bond_communities(ids(9), planted_network(again), 1.0)), planted);
}

TEST(GranuleCommunities, PartitionDependsOnIdsNotOnStorageOrBondOrder) {
  // 40 particles on a ring of 8 cliques of 5, weak bonds between neighbouring cliques.
  constexpr Index kN = 40;
  std::vector<Bond> bonds;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> strong(1.0, 2.0), weak(0.01, 0.2);
  for (Index c = 0; c < 8; ++c) {
    for (Index a = 0; a < 5; ++a) {
      for (Index b = a + 1; b < 5; ++b)
        bonds.push_back({5 * c + a, 5 * c + b, 0.0, strong(rng), 0.0});
    }
    bonds.push_back({5 * c + 4, (5 * c + 5) % kN, 0.0, weak(rng), 0.0});
  }
  for (Bond& b : bonds) {
    if (b.i > b.j) std::swap(b.i, b.j);
  }
  const std::vector<std::size_t> root = bond_communities(ids(kN), bonds, 1.0);
  // Each clique is one community, represented by its smallest id.
  for (Index i = 0; i < kN; ++i) EXPECT_EQ(root[i], 5 * (i / 5)) << i;

  // The same frame stored in another order (ids move with the particles), bonds shuffled.
  std::vector<Index> slot(kN);  // slot[old] = new storage slot
  std::iota(slot.begin(), slot.end(), Index{0});
  std::shuffle(slot.begin(), slot.end(), rng);
  std::vector<std::uint32_t> id(kN);
  for (Index i = 0; i < kN; ++i) id[slot[i]] = i;
  std::vector<Bond> moved = bonds;
  for (Bond& b : moved) {
    b.i = slot[b.i];
    b.j = slot[b.j];
    if (b.i > b.j) std::swap(b.i, b.j);
  }
  std::shuffle(moved.begin(), moved.end(), rng);
  const std::vector<std::size_t> root2 = bond_communities(id, moved, 1.0);
  for (Index i = 0; i < kN; ++i) EXPECT_EQ(id[root2[slot[i]]], root[i]) << i;
}

TEST(GranuleCommunities, ZeroForceJoinsNothingAndBadInputIsRefused) {
  const std::vector<Bond> dry = {{0, 1, 1e-9, 0.0, 1.0}, {1, 2, 1e-9, 0.0, 1.0}};
  EXPECT_EQ(bond_communities(ids(3), dry, 1.0), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_THROW(bond_communities(ids(3), dry, 0.0), std::invalid_argument);
  EXPECT_THROW(bond_communities(ids(3), {{{0, 3, 0.0, 1.0, 0.0}}}, 1.0), std::invalid_argument);
}

// The frame analysis: an 8 x 8 lattice bridged everywhere by weak bonds (0.02 N) with two strongly
// bound clusters (1 N) inside. Components: one cluster of 64. Communities: the two clusters are
// granules of their own, whatever the weak lattice splits into, and every community is held
// together by bonds (Leiden's communities are connected).
TEST(GranuleCommunities, FrameSeparatesStronglyBoundClustersInAPercolatingNetwork) {
  constexpr int kSide = 8;
  std::vector<Vec3> position;
  std::vector<double> radius, mass;
  std::vector<std::uint32_t> id;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      position.emplace_back(0.002 * x, 0.002 * y, 0.0);
      radius.push_back(0.001);
      mass.push_back(1.0);
      id.push_back(static_cast<std::uint32_t>(y * kSide + x));
    }
  }
  const auto slot = [](int x, int y) { return static_cast<Index>(y * kSide + x); };
  const auto in_cluster = [](int x, int y) {
    return (x <= 2 && y <= 2) ? 1 : ((x >= 5 && y >= 5) ? 2 : 0);  // 3 x 3 and 3 x 3
  };
  std::vector<Bond> bonds;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (x + dx >= kSide || y + dy >= kSide) continue;
        const int c = in_cluster(x, y);
        const bool same = c != 0 && c == in_cluster(x + dx, y + dy);
        bonds.push_back({slot(x, y), slot(x + dx, y + dy), 0.0, same ? 1.0 : 0.02, 0.0});
      }
    }
  }
  AgglomerateInput in;
  in.position = position;
  in.radius = radius;
  in.mass = mass;
  in.id = id;
  in.bonds = bonds;
  const AgglomerateFrame plain = find_agglomerates(in, {});
  EXPECT_EQ(plain.stats.largest, 64u);
  AgglomerateOptions o;
  o.community = true;
  const AgglomerateFrame c = find_agglomerates(in, o);
  EXPECT_EQ(c.stats.criterion, "community(resolution=1)");
  EXPECT_DOUBLE_EQ(c.stats.largest_plain_share, 1.0);
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const int k = in_cluster(x, y);
      if (k == 0) continue;
      const Index first = k == 1 ? slot(0, 0) : slot(5, 5);
      EXPECT_EQ(c.label[slot(x, y)], c.label[first]) << x << "," << y;
      EXPECT_EQ(c.size_of[slot(x, y)], 9u) << x << "," << y;  // nothing weak joins them
    }
  }
  EXPECT_NE(c.label[slot(0, 0)], c.label[slot(5, 5)]);
  // Connected: within each community, the bonds between members join them all.
  std::map<std::uint32_t, std::vector<Index>> members;
  for (Index i = 0; i < 64; ++i) members[c.label[i]].push_back(i);
  for (const auto& [label, m] : members) {
    std::vector<char> seen(64, 0);
    std::vector<Index> queue = {m.front()};
    seen[m.front()] = 1;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      for (const Bond& b : bonds) {
        const Index other = b.i == queue[q] ? b.j : (b.j == queue[q] ? b.i : Index(64));
        if (other < 64 && !seen[other] && c.label[other] == label) {
          seen[other] = 1;
          queue.push_back(other);
        }
      }
    }
    EXPECT_EQ(queue.size(), m.size()) << "community " << label << " is not connected";
  }
}

}  // namespace
}  // namespace drumlab::test
