#include "engine/parallel/ghost_layer.hpp"

#include <algorithm>
#include <cmath>

#include "engine/contact/contact_model.hpp"
#include "engine/periodic.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab {

GhostReach ghost_reach(double max_radius, double pair_range, double verlet_skin) {
  return {max_radius + pair_range + kTouchTolerance + verlet_skin, max_radius};
}

GhostReach ghost_reach(const SceneConfig& scene) {
  const auto parsed = parse_search_method(scene.search_method);
  const bool verlet = parsed && parsed->verlet;
  const double skin = verlet ? scene.performance.verlet_skin * scene.min_radius() : 0.0;
  return ghost_reach(scene.max_radius(), ContactModel(scene).max_pair_range(), skin);
}

double box_distance(const Box& box, const Vec3& x, std::optional<double> period_z) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    double gap = 0.0;
    if (k == 2 && period_z) {
      const double centre = 0.5 * (box.lo.z() + box.hi.z());
      const double half = 0.5 * (box.hi.z() - box.lo.z());
      gap = std::max(0.0, std::abs(nearest_image_z(x.z() - centre, *period_z)) - half);
    } else {
      gap = std::max({0.0, box.lo[k] - x[k], x[k] - box.hi[k]});
    }
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

namespace {

/// Calls f(rank) for every leaf of the subtree `id` whose box lies within `reach` of x.
template <class F>
void ranks_near(const Decomposition& d, int id, const Vec3& x, double reach,
                std::optional<double> period_z, F& f) {
  const RcbNode& node = d.nodes[static_cast<std::size_t>(id)];
  if (box_distance(node.box, x, period_z) > reach) return;
  if (node.leaf()) {
    f(node.rank_begin);
    return;
  }
  ranks_near(d, node.left, x, reach, period_z, f);
  ranks_near(d, node.right, x, reach, period_z, f);
}

}  // namespace

void ranks_within(const Decomposition& d, const Vec3& x, double reach,
                  std::optional<double> period_z, std::vector<int>& out) {
  out.clear();
  if (d.nodes.empty()) return;
  auto add = [&](int rank) { out.push_back(rank); };
  ranks_near(d, 0, x, reach, period_z, add);
  std::sort(out.begin(), out.end());
}

GhostLayer ghost_layer(const Decomposition& d, std::span<const Vec3> position,
                       std::span<const double> radius, GhostReach reach,
                       std::optional<double> period_z) {
  GhostLayer g;
  g.reach = reach;
  const auto ranks = static_cast<std::size_t>(d.ranks());
  g.ghosts.assign(ranks, {});
  g.sources.assign(ranks, {});
  for (std::size_t i = 0; i < position.size(); ++i) {
    const int own = d.owner[i];
    auto add = [&](int rank) {
      if (rank != own) g.ghosts[static_cast<std::size_t>(rank)].push_back(static_cast<Index>(i));
    };
    ranks_near(d, 0, position[i], reach.of(radius[i]), period_z, add);
  }
  for (std::size_t r = 0; r < ranks; ++r) {
    std::vector<int>& s = g.sources[r];
    for (const Index j : g.ghosts[r]) s.push_back(d.owner[j]);
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
  }
  return g;
}

}  // namespace drumlab
