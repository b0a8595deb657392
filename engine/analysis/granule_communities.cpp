#include "engine/analysis/granule_communities.hpp"

#include <igraph.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

#include <fmt/format.h>

namespace drumlab {
namespace {

/// The seed of igraph's generator before each detection (any fixed value: a partition is a
/// function of the frame alone).
constexpr igraph_integer_t kSeed = 20251006;

/// igraph keeps global state (its random generator, its error handlers) and Debian builds it
/// without thread-local storage: one detection at a time.
std::mutex& igraph_mutex() {
  static std::mutex m;
  return m;
}

void check(igraph_error_t code, const char* what) {
  if (code != IGRAPH_SUCCESS) {
    throw std::runtime_error(
        fmt::format("community detection: igraph {} failed: {}", what, igraph_strerror(code)));
  }
}

/// Owns an igraph object and destroys it with its function on every path.
template <class T, void (*Destroy)(T*)>
struct Owned {
  T value;
  bool live = false;
  ~Owned() {
    if (live) Destroy(&value);
  }
};

struct Edge {
  igraph_integer_t a, b;  ///< ranks by stable id, a < b
  double weight;
};

}  // namespace

std::vector<std::size_t> bond_communities(std::span<const std::uint32_t> id,
                                          std::span<const Bond> bonds, double resolution) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument(
        fmt::format("bond_communities: resolution {} is not positive", resolution));
  }
  const std::size_t n = id.size();
  // Nodes in the order of the stable ids.
  std::vector<std::size_t> slot_of_rank(n);
  std::iota(slot_of_rank.begin(), slot_of_rank.end(), std::size_t{0});
  std::sort(slot_of_rank.begin(), slot_of_rank.end(),
            [&](std::size_t l, std::size_t r) { return id[l] < id[r]; });
  std::vector<igraph_integer_t> rank(n);
  for (std::size_t k = 0; k < n; ++k) rank[slot_of_rank[k]] = static_cast<igraph_integer_t>(k);

  std::vector<Edge> edges;
  edges.reserve(bonds.size());
  for (const Bond& b : bonds) {
    if (b.i >= n || b.j >= n || b.i == b.j) {
      throw std::invalid_argument(
          fmt::format("bond_communities: bond ({}, {}) out of range of {} particles", b.i, b.j, n));
    }
    if (!(b.force > 0.0) || !std::isfinite(b.force)) continue;
    const auto [a, c] = std::minmax(rank[b.i], rank[b.j]);
    edges.push_back({a, c, b.force});
  }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& l, const Edge& r) { return std::tie(l.a, l.b) < std::tie(r.a, r.b); });
  // Two bonds between one pair (none today) count as one of their summed force.
  std::size_t kept = 0;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    if (kept > 0 && edges[kept - 1].a == edges[k].a && edges[kept - 1].b == edges[k].b) {
      edges[kept - 1].weight += edges[k].weight;
    } else {
      edges[kept++] = edges[k];
    }
  }
  edges.resize(kept);

  std::vector<igraph_integer_t> community(n);
  std::iota(community.begin(), community.end(), igraph_integer_t{0});
  if (!edges.empty()) {
    const std::lock_guard<std::mutex> lock(igraph_mutex());
    igraph_set_error_handler(igraph_error_handler_ignore);
    igraph_set_warning_handler(igraph_warning_handler_ignore);
    const auto m = static_cast<igraph_integer_t>(edges.size());
    Owned<igraph_vector_int_t, igraph_vector_int_destroy> ends, membership;
    Owned<igraph_vector_t, igraph_vector_destroy> weights, strength;
    Owned<igraph_t, igraph_destroy> graph;
    check(igraph_vector_int_init(&ends.value, 2 * m), "vector");
    ends.live = true;
    check(igraph_vector_init(&weights.value, m), "vector");
    weights.live = true;
    double total = 0.0;
    for (igraph_integer_t e = 0; e < m; ++e) {
      VECTOR(ends.value)[2 * e] = edges[e].a;
      VECTOR(ends.value)[2 * e + 1] = edges[e].b;
      VECTOR(weights.value)[e] = edges[e].weight;
      total += edges[e].weight;
    }
    check(igraph_create(&graph.value, &ends.value, static_cast<igraph_integer_t>(n),
                        IGRAPH_UNDIRECTED),
          "create");
    graph.live = true;
    check(igraph_vector_init(&strength.value, 0), "vector");
    strength.live = true;
    check(igraph_strength(&graph.value, &strength.value, igraph_vss_all(), IGRAPH_ALL, IGRAPH_LOOPS,
                          &weights.value),
          "strength");
    check(igraph_vector_int_init(&membership.value, 0), "vector");
    membership.live = true;
    igraph_rng_seed(igraph_rng_default(), kSeed);
    igraph_integer_t clusters = 0;
    igraph_real_t quality = 0.0;
    // Modularity with Leiden: node weights are the strengths, the resolution is gamma / (2W).
    check(igraph_community_leiden(&graph.value, &weights.value, &strength.value,
                                  resolution / (2.0 * total), /*beta=*/0.01, /*start=*/false,
                                  /*n_iterations=*/-1, &membership.value, &clusters, &quality),
          "community_leiden");
    for (std::size_t k = 0; k < n; ++k) community[k] = VECTOR(membership.value)[k];
  }
  // Each community's representative: its member of the smallest stable id (the lowest rank).
  std::vector<std::size_t> first(n, n);
  std::vector<std::size_t> root(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t& f = first[static_cast<std::size_t>(community[k])];
    if (f == n) f = slot_of_rank[k];
    root[slot_of_rank[k]] = f;
  }
  return root;
}

}  // namespace drumlab
