#include "engine/analysis/agglomerates.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "engine/analysis/disjoint_sets.hpp"
#include "engine/analysis/granule_communities.hpp"
#include "engine/contact/cohesion_loops.hpp"
#include "engine/periodic.hpp"
#include "engine/simulation.hpp"
#include "engine/spray/droplet_cloud.hpp"

namespace drumlab {
namespace {

void check_input(const AgglomerateInput& in) {
  const std::size_t n = in.position.size();
  if (in.radius.size() != n || in.mass.size() != n || in.id.size() != n ||
      (!in.film.empty() && in.film.size() != n)) {
    throw std::invalid_argument("find_agglomerates: per-particle arrays differ in length");
  }
  for (const Bond& b : in.bonds) {
    if (b.i >= n || b.j >= n || b.i == b.j) {
      throw std::invalid_argument(fmt::format(
          "find_agglomerates: bond ({}, {}) out of range of {} particles", b.i, b.j, n));
    }
  }
}

/// Mass-weighted percentile q of the diameters: the smallest diameter at which the cumulative
/// mass (agglomerates by increasing diameter) reaches q of the total.
double mass_percentile(const std::vector<std::pair<double, double>>& by_diameter, double total,
                       double q) {
  double cumulative = 0.0;
  for (const auto& [d, m] : by_diameter) {
    cumulative += m;
    if (cumulative >= q * total) return d;
  }
  return by_diameter.empty() ? 0.0 : by_diameter.back().first;
}

/// Members unwrapped along the bonds of their component (breadth first from the first member), so
/// that every bond is its minimum image: a cluster across periodic ends stays in one piece.
std::vector<Vec3> unwrapped_positions(const AgglomerateInput& in,
                                      const std::vector<std::size_t>& root,
                                      const std::vector<const Bond*>& used) {
  const std::size_t n = in.position.size();
  std::vector<Vec3> x(in.position.begin(), in.position.end());
  if (in.period <= 0.0 || used.empty()) return x;
  std::vector<std::size_t> start(n + 1, 0);
  for (const Bond* b : used) {
    ++start[b->i + 1];
    ++start[b->j + 1];
  }
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  std::vector<Index> next(start[n]);
  for (const Bond* b : used) {
    next[fill[b->i]++] = b->j;
    next[fill[b->j]++] = b->i;
  }
  std::vector<char> seen(n, 0);
  std::vector<Index> queue;
  for (std::size_t s = 0; s < n; ++s) {
    if (seen[s] || start[s] == start[s + 1]) continue;
    seen[s] = 1;
    queue.assign(1, static_cast<Index>(s));
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const Index a = queue[q];
      for (std::size_t k = start[a]; k < start[a + 1]; ++k) {
        const Index b = next[k];
        if (seen[b] || root[b] != root[a]) continue;
        seen[b] = 1;
        x[b] = x[a] + nearest_image(in.position[b], in.position[a], in.period);
        queue.push_back(b);
      }
    }
  }
  return x;
}

}  // namespace

bool bond_joins(const Bond& b, const AgglomerateOptions& o) {
  return o.min_bond_age <= 0.0 || b.age >= o.min_bond_age;
}

namespace {

/// The bonds that join (unite) and the root of every primary; the largest cluster of all bonds,
/// whatever the criterion, goes to `stats`.
struct Clusters {
  std::vector<std::size_t> root;
  std::vector<const Bond*> used;
};

Clusters cluster_primaries(const AgglomerateInput& in, const AgglomerateOptions& options,
                           AgglomerateStats& st) {
  const std::size_t n = in.position.size();
  DisjointSets plain(n);
  DisjointSets sets(n);
  Clusters c;
  for (const Bond& b : in.bonds) {
    plain.unite(b.i, b.j);
    if (!options.community && bond_joins(b, options)) {
      sets.unite(b.i, b.j);
      c.used.push_back(&b);
    }
  }
  std::size_t largest_plain = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (plain.find(i) == i) largest_plain = std::max(largest_plain, plain.size_of_root(i));
  }
  st.largest_plain_share = n ? static_cast<double>(largest_plain) / static_cast<double>(n) : 0.0;
  if (options.community) {
    c.root = bond_communities(in.id, in.bonds, options.resolution);
    for (const Bond& b : in.bonds) {
      if (c.root[b.i] == c.root[b.j]) c.used.push_back(&b);
    }
    return c;
  }
  c.root.resize(n);
  for (std::size_t i = 0; i < n; ++i) c.root[i] = sets.find(i);
  return c;
}

/// One agglomerate per root, numbered in order of first appearance (`member_of[i]`): primaries,
/// mass, sum of d^3, liquid of the films and of the bonds inside.
std::vector<Agglomerate> sum_members(const AgglomerateInput& in, const Clusters& c,
                                     std::vector<std::size_t>& member_of) {
  const std::size_t n = in.position.size();
  std::vector<std::size_t> slot_of_root(n, n);
  std::vector<Agglomerate> a;
  member_of.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t& s = slot_of_root[c.root[i]];
    if (s == n) {
      s = a.size();
      a.push_back({});
      a.back().id = in.id[i];
    }
    member_of[i] = s;
    Agglomerate& g = a[s];
    g.id = std::min(g.id, in.id[i]);
    ++g.primaries;
    g.mass += in.mass[i];
    g.diameter += std::pow(2.0 * in.radius[i], 3);  // sum d^3 until the cube root below
    if (!in.film.empty()) g.liquid += in.film[i];
  }
  for (const Bond& b : in.bonds) {
    if (c.root[b.i] == c.root[b.j]) a[member_of[b.i]].liquid += b.volume;
  }
  return a;
}

/// Centre of mass (on the unwrapped positions, wrapped back into the period), volume-equivalent
/// diameter and radius of gyration of every agglomerate.
void shape_agglomerates(const AgglomerateInput& in, const Clusters& c,
                        const std::vector<std::size_t>& member_of, std::vector<Agglomerate>& a) {
  const std::size_t n = in.position.size();
  const std::vector<Vec3> x = unwrapped_positions(in, c.root, c.used);
  for (std::size_t i = 0; i < n; ++i) a[member_of[i]].centre += in.mass[i] * x[i];
  for (Agglomerate& g : a) {
    g.centre /= g.mass;
    g.diameter = std::cbrt(g.diameter);
  }
  for (std::size_t i = 0; i < n; ++i) {
    Agglomerate& g = a[member_of[i]];
    g.radius_of_gyration += in.mass[i] * (x[i] - g.centre).squaredNorm();
  }
  for (Agglomerate& g : a) {
    g.radius_of_gyration = std::sqrt(g.radius_of_gyration / g.mass);
    if (in.period > 0.0) {
      g.centre.z() = std::fmod(g.centre.z(), in.period);
      if (g.centre.z() < 0.0) g.centre.z() += in.period;
    }
  }
}

/// Count, largest, mean size (agglomerates of two or more) and the mass-weighted d10, d50, d90.
void size_statistics(const std::vector<Agglomerate>& a, AgglomerateStats& st) {
  double total_mass = 0.0;
  std::vector<std::pair<double, double>> by_diameter;
  by_diameter.reserve(a.size());
  std::size_t members_in_clusters = 0;
  for (const Agglomerate& g : a) {
    st.largest = std::max(st.largest, g.primaries);
    by_diameter.emplace_back(g.diameter, g.mass);
    total_mass += g.mass;
    if (g.primaries >= 2) {
      ++st.count;
      members_in_clusters += g.primaries;
    }
  }
  st.mean_size = st.count ? static_cast<double>(members_in_clusters) / st.count : 0.0;
  std::sort(by_diameter.begin(), by_diameter.end());
  st.d10 = mass_percentile(by_diameter, total_mass, 0.1);
  st.d50 = mass_percentile(by_diameter, total_mass, 0.5);
  st.d90 = mass_percentile(by_diameter, total_mass, 0.9);
}

}  // namespace

AgglomerateFrame find_agglomerates(const AgglomerateInput& in, const AgglomerateOptions& options) {
  check_input(in);
  const std::size_t n = in.position.size();
  AgglomerateFrame out;
  AgglomerateStats& st = out.stats;
  st.time = in.time;
  st.criterion = criterion_name(options);
  st.bonds = in.bonds.size();
  for (const Bond& b : in.bonds) st.bridge_liquid += b.volume;
  for (double f : in.film) st.free_liquid += f;
  st.wall_liquid = in.wall_liquid;
  st.spray = in.spray;

  const Clusters clusters = cluster_primaries(in, options, st);
  std::vector<std::size_t> member_of;
  std::vector<Agglomerate> a = sum_members(in, clusters, member_of);
  shape_agglomerates(in, clusters, member_of, a);
  out.label.resize(n);
  out.size_of.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.label[i] = a[member_of[i]].id;
    out.size_of[i] = a[member_of[i]].primaries;
  }
  size_statistics(a, st);
  std::sort(a.begin(), a.end(),
            [](const Agglomerate& l, const Agglomerate& r) { return l.id < r.id; });
  out.agglomerates = std::move(a);
  return out;
}

bool scene_has_bonds(const SceneConfig& scene) {
  return scene.liquid.enabled || scene.cohesion.enabled;
}

double default_granule_age(double omega) {
  return omega != 0.0 ? 2.0 * std::numbers::pi / std::abs(omega) : 0.0;
}

AgglomerateOptions granule_options(double omega, const GranuleCriterion& criterion) {
  AgglomerateOptions o;
  switch (criterion.method) {
    case GranuleMethod::age:
      o.min_bond_age = criterion.age < 0.0 ? default_granule_age(omega) : criterion.age;
      break;
    case GranuleMethod::components:
      break;
    case GranuleMethod::community:
      if (!(criterion.resolution > 0.0) || !std::isfinite(criterion.resolution)) {
        throw InputError(
            fmt::format("--granule-resolution: {} is not a positive number", criterion.resolution));
      }
      o.community = true;
      o.resolution = criterion.resolution;
      break;
  }
  return o;
}

std::string criterion_name(const AgglomerateOptions& options) {
  if (options.community) return fmt::format("community(resolution={:.6g})", options.resolution);
  if (options.min_bond_age <= 0.0) return "components";
  return fmt::format("bond_age>={:.6g}s", options.min_bond_age);
}

AgglomerateInput agglomerate_input(const Simulation& sim, std::vector<Bond>& bonds) {
  sim.bonds(bonds);
  const Particles& p = sim.particles();
  AgglomerateInput in;
  in.position = p.position;
  in.radius = p.radius;
  in.mass = p.mass;
  in.id = p.id;
  if (const std::vector<double>* film = p.find_array(kLiquidFilmArray)) in.film = *film;
  in.bonds = bonds;
  in.wall_liquid = wall_bridge_liquid(p);
  if (const DropletCloud* spray = sim.spray()) {
    const SprayTotals t = spray->totals();
    in.spray = {t.sprayed, t.airborne, t.lost, t.on_wall};
  }
  in.period = sim.search_input().period_z.value_or(0.0);
  in.time = sim.time();
  return in;
}

std::vector<std::uint32_t> agglomerate_labels(const Simulation& sim,
                                              const GranuleCriterion& granule) {
  std::vector<Bond> bonds;
  return find_agglomerates(agglomerate_input(sim, bonds),
                           granule_options(sim.scene().drum.omega, granule))
      .label;
}

std::string agglomerate_csv_header() {
  return "time,criterion,agglomerates,mean_size,largest,d10,d50,d90,bonds,free_liquid,"
         "bridge_liquid,wall_bridge_liquid,largest_plain_share,sprayed_liquid,airborne_liquid,"
         "lost_liquid,wall_film_liquid";
}

std::string agglomerate_csv_row(const AgglomerateStats& s) {
  return fmt::format(
      "{:.9g},{},{},{:.6g},{},{:.6g},{:.6g},{:.6g},{},{:.12g},{:.12g},{:.12g},{:.6g},{:.12g},"
      "{:.12g},{:.12g},{:.12g}",
      s.time, s.criterion, s.count, s.mean_size, s.largest, s.d10, s.d50, s.d90, s.bonds,
      s.free_liquid, s.bridge_liquid, s.wall_liquid, s.largest_plain_share, s.spray.sprayed,
      s.spray.airborne, s.spray.lost, s.spray.on_wall);
}

}  // namespace drumlab
