// Agglomerates of constructed bond lists (engine/analysis/agglomerates.hpp): components, ids,
// mass, volume-equivalent diameter, centre and radius of gyration against hand-computed values,
// a cluster across periodic ends kept whole, liquid held, and the granule criterion on a
// percolating network of young bonds around two old clusters; then a live wet drum.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/analysis/agglomerates.hpp"
#include "engine/simulation.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

struct Frame {
  std::vector<Vec3> position;
  std::vector<double> radius, mass, film;
  std::vector<std::uint32_t> id;
  std::vector<Bond> bonds;
  double period = 0.0;

  void add(const Vec3& x, std::uint32_t stable_id, double r = 0.001, double m = 1.0) {
    position.push_back(x);
    radius.push_back(r);
    mass.push_back(m);
    id.push_back(stable_id);
  }
  void bond(Index i, Index j, double age, double volume = 0.0) {
    bonds.push_back({std::min(i, j), std::max(i, j), volume, 1e-6, age});
  }
  AgglomerateInput input() const {
    AgglomerateInput in;
    in.position = position;
    in.radius = radius;
    in.mass = mass;
    in.id = id;
    in.film = film;
    in.bonds = bonds;
    in.period = period;
    return in;
  }
};

const Agglomerate& by_id(const AgglomerateFrame& f, std::uint32_t id) {
  for (const Agglomerate& a : f.agglomerates) {
    if (a.id == id) return a;
  }
  throw std::logic_error("no agglomerate with that id");
}

TEST(Agglomerates, ComponentsWithHandComputedProperties) {
  Frame f;
  // A chain of three (stable ids 7, 3, 9) along x, masses 1, 1, 2; a pair (ids 5, 4); a single 1.
  f.add({0.0, 0.0, 0.0}, 7);
  f.add({0.002, 0.0, 0.0}, 3);
  f.add({0.004, 0.0, 0.0}, 9, 0.001, 2.0);
  f.add({0.1, 0.0, 0.0}, 5);
  f.add({0.1, 0.002, 0.0}, 4);
  f.add({-0.1, 0.0, 0.0}, 1, 0.002);
  f.bond(0, 1, 0.0, 1e-9);
  f.bond(1, 2, 0.0, 2e-9);
  f.bond(3, 4, 0.0, 4e-9);
  f.film = {1e-10, 0.0, 0.0, 0.0, 0.0, 8e-10};
  const AgglomerateFrame out = find_agglomerates(f.input(), {});
  ASSERT_EQ(out.agglomerates.size(), 3u);
  const Agglomerate& chain = by_id(out, 3);  // the smallest stable id of {7, 3, 9}
  EXPECT_EQ(chain.primaries, 3u);
  EXPECT_DOUBLE_EQ(chain.mass, 4.0);
  // Three spheres of diameter 2 mm: d = 2 mm * 3^(1/3).
  EXPECT_NEAR(chain.diameter, 0.002 * std::cbrt(3.0), 1e-15);
  // Centre (0 + 0.002 + 2 * 0.004) / 4 = 0.0025; Rg^2 = (0.0025^2 + 0.0005^2 + 2 * 0.0015^2) / 4.
  EXPECT_NEAR(chain.centre.x(), 0.0025, 1e-15);
  EXPECT_NEAR(chain.radius_of_gyration, std::sqrt((6.25e-6 + 0.25e-6 + 2 * 2.25e-6) / 4.0), 1e-15);
  EXPECT_NEAR(chain.liquid, 1e-10 + 3e-9, 1e-24);  // film of id 7 + both bridges
  EXPECT_EQ(by_id(out, 4).primaries, 2u);
  EXPECT_NEAR(by_id(out, 4).liquid, 4e-9, 1e-24);
  EXPECT_EQ(by_id(out, 1).primaries, 1u);
  EXPECT_EQ(out.label, (std::vector<std::uint32_t>{3, 3, 3, 4, 4, 1}));
  EXPECT_EQ(out.size_of, (std::vector<std::size_t>{3, 3, 3, 2, 2, 1}));

  const AgglomerateStats& s = out.stats;
  EXPECT_EQ(s.criterion, "components");
  EXPECT_EQ(s.count, 2u);
  EXPECT_DOUBLE_EQ(s.mean_size, 2.5);
  EXPECT_EQ(s.largest, 3u);
  EXPECT_EQ(s.bonds, 3u);
  EXPECT_NEAR(s.free_liquid, 9e-10, 1e-24);
  EXPECT_NEAR(s.bridge_liquid, 7e-9, 1e-24);
  EXPECT_DOUBLE_EQ(s.largest_plain_share, 0.5);
  // Mass-weighted over the three: pair 2 kg (d = 2 mm * 2^(1/3)), single 1 kg (4 mm), chain 4 kg.
  // By diameter: pair 2.52 mm (cum 2/7), chain 2.88 mm (6/7), single 4 mm (7/7).
  EXPECT_NEAR(s.d10, 0.002 * std::cbrt(2.0), 1e-15);
  EXPECT_NEAR(s.d50, 0.002 * std::cbrt(3.0), 1e-15);
  EXPECT_NEAR(s.d90, 0.004, 1e-15);
}

TEST(Agglomerates, ClusterAcrossPeriodicEndsIsNotTorn) {
  Frame f;
  f.period = 0.05;
  f.add({0.0, 0.0, 0.049}, 2);  // 1 mm below the far end
  f.add({0.0, 0.0, 0.001}, 1);  // 1 mm above z = 0: 2 mm apart through the ends
  f.add({0.0, 0.0, 0.003}, 0);
  f.bond(0, 1, 0.0);
  f.bond(1, 2, 0.0);
  const AgglomerateFrame out = find_agglomerates(f.input(), {});
  ASSERT_EQ(out.agglomerates.size(), 1u);
  const Agglomerate& a = out.agglomerates[0];
  // Unwrapped: -0.001, 0.001, 0.003: centre 0.001, Rg^2 = (4 + 0 + 4) e-6 / 3.
  EXPECT_NEAR(a.centre.z(), 0.001, 1e-15);
  EXPECT_NEAR(a.radius_of_gyration, std::sqrt(8e-6 / 3.0), 1e-15);
  // Without the minimum image the centre would sit mid-drum (0.0177) with Rg ~ 22 mm.
  f.period = 0.0;
  EXPECT_GT(find_agglomerates(f.input(), {}).agglomerates[0].radius_of_gyration, 0.02);
}

// The pitfall of a dense wet flowing bed: a lattice in which every neighbour is bridged by young
// bonds (formed in the last passage through the flowing layer) percolates, and two dense clusters
// of old bonds sit inside it. Plain components: one cluster holding the whole bed; the
// persistence criterion: the two old clusters.
TEST(Agglomerates, GranuleCriterionSeparatesOldClustersInAPercolatingNetwork) {
  Frame f;
  constexpr int kSide = 8;  // an 8 x 8 lattice, spacing 2 mm
  const auto slot = [](int x, int y) { return static_cast<Index>(y * kSide + x); };
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) f.add({0.002 * x, 0.002 * y, 0.0}, slot(x, y) + 100);
  }
  const auto in_cluster = [](int x, int y) {
    const bool a = x <= 2 && y <= 2;            // 3 x 3 in one corner
    const bool b = x >= 5 && y >= 5 && x <= 6;  // 2 x 3 in the other
    return a ? 1 : (b ? 2 : 0);
  };
  const double young = 0.01, old = 2.0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (x + dx >= kSide || y + dy >= kSide) continue;
        const int c = in_cluster(x, y);
        const bool same = c != 0 && c == in_cluster(x + dx, y + dy);
        f.bond(slot(x, y), slot(x + dx, y + dy), same ? old : young);
      }
    }
  }
  const AgglomerateFrame plain = find_agglomerates(f.input(), {});
  EXPECT_EQ(plain.stats.count, 1u);
  EXPECT_EQ(plain.stats.largest, 64u);
  EXPECT_DOUBLE_EQ(plain.stats.largest_plain_share, 1.0);

  const AgglomerateFrame granules = find_agglomerates(f.input(), {1.0});
  EXPECT_EQ(granules.stats.criterion, "bond_age>=1s");
  EXPECT_EQ(granules.stats.count, 2u);
  EXPECT_EQ(granules.stats.largest, 9u);
  EXPECT_DOUBLE_EQ(granules.stats.mean_size, 7.5);
  EXPECT_DOUBLE_EQ(granules.stats.largest_plain_share, 1.0);  // reported beside the criterion
  EXPECT_EQ(by_id(granules, 100).primaries, 9u);              // slot (0, 0): id 100
  EXPECT_EQ(by_id(granules, slot(5, 5) + 100).primaries, 6u);
  EXPECT_EQ(granules.agglomerates.size(), 2u + (64u - 15u));
}

TEST(Agglomerates, IdFollowsTheSmallestMemberAcrossFramesAndBadInputIsRefused) {
  Frame f;
  f.add({0.0, 0.0, 0.0}, 12);
  f.add({0.002, 0.0, 0.0}, 10);
  f.add({0.004, 0.0, 0.0}, 11);
  f.bond(0, 1, 0.0);
  EXPECT_EQ(find_agglomerates(f.input(), {}).label[0], 10u);
  f.bond(1, 2, 0.0);  // grows by a larger id: the id stays
  EXPECT_EQ(find_agglomerates(f.input(), {}).label[2], 10u);
  f.bonds.push_back({0, 3, 0.0, 0.0, 0.0});
  EXPECT_THROW(find_agglomerates(f.input(), {}), std::invalid_argument);
}

// A live wet drum: bridges form, each bond joins two particles of the same agglomerate, the
// largest plain component is at least the largest granule.
TEST(Agglomerates, LiveWetDrumHasBridgedAgglomerates) {
  SceneConfig scene = output_scene();
  scene.liquid.enabled = true;
  scene.liquid.surface_tension = scene.liquid.wall_surface_tension = 0.072;
  scene.liquid.bridge_volume = 1e-9;
  ASSERT_TRUE(scene_has_bonds(scene));
  EXPECT_FALSE(scene_has_bonds(output_scene()));
  EXPECT_NEAR(default_granule_age(scene.drum.omega), 2.0 * M_PI / 3.0, 1e-12);
  EXPECT_EQ(granule_options(3.0, {}).min_bond_age, default_granule_age(3.0));
  EXPECT_EQ(granule_options(3.0, {GranuleMethod::age, 0.0}).min_bond_age, 0.0);
  EXPECT_EQ(granule_options(0.0, {}).min_bond_age, 0.0);  // a drum at rest: plain
  EXPECT_EQ(granule_options(3.0, {GranuleMethod::components, 5.0}).min_bond_age, 0.0);
  EXPECT_FALSE(granule_options(3.0, {GranuleMethod::components}).community);
  const AgglomerateOptions community = granule_options(3.0, {GranuleMethod::community, -1.0, 2.5});
  EXPECT_TRUE(community.community);
  EXPECT_EQ(community.resolution, 2.5);
  EXPECT_EQ(criterion_name(community), "community(resolution=2.5)");
  EXPECT_THROW(granule_options(3.0, {GranuleMethod::community, -1.0, 0.0}), InputError);
  auto sim = settled_simulation(scene, 300);
  std::vector<Bond> bonds;
  const AgglomerateInput in = agglomerate_input(*sim, bonds);
  ASSERT_GT(bonds.size(), 50u);
  const AgglomerateFrame out = find_agglomerates(in, {});
  for (const Bond& b : bonds) EXPECT_EQ(out.label[b.i], out.label[b.j]);
  EXPECT_GE(out.stats.count, 1u);
  EXPECT_EQ(out.stats.bonds, bonds.size());
  EXPECT_EQ(out.stats.free_liquid, 0.0);  // no film array: no film
  EXPECT_NEAR(out.stats.bridge_liquid, 1e-9 * static_cast<double>(bonds.size()), 1e-18);
  const AgglomerateFrame aged = find_agglomerates(in, {sim->time()});
  EXPECT_LE(aged.stats.largest, out.stats.largest);
  EXPECT_DOUBLE_EQ(aged.stats.largest_plain_share, out.stats.largest_plain_share);
}

}  // namespace
}  // namespace drumlab::test
