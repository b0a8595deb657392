#include "engine/parallel/exchange_cost.hpp"

#include <algorithm>

namespace drumlab {

PairsAcross pairs_across(const Decomposition& d, std::span<const std::size_t> row,
                         std::span<const Index> col) {
  PairsAcross p;
  p.across.assign(static_cast<std::size_t>(d.ranks()), 0);
  for (std::size_t i = 0; i + 1 < row.size(); ++i) {
    const int a = d.owner[i];
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const int b = d.owner[col[k]];
      if (a == b) continue;
      ++p.across[static_cast<std::size_t>(a)];
      ++p.across[static_cast<std::size_t>(b)];
    }
  }
  p.total = row.empty() ? 0 : row.back() - row.front();
  return p;
}

DecompositionCost decomposition_cost(const Decomposition& d, const GhostLayer& g, double rate,
                                     const NetworkModel& net, std::span<const double> rank_work,
                                     const PairsAcross* pairs) {
  if (rank_work.empty()) rank_work = d.owned_weight;
  DecompositionCost c;
  c.rate = rate;
  std::size_t total = 0;
  double total_weight = 0.0;
  for (const double w : rank_work) total_weight += w;
  for (std::size_t r : d.owned) total += r;
  c.step_serial = static_cast<double>(total) / rate;
  for (int r = 0; r < d.ranks(); ++r) {
    const auto k = static_cast<std::size_t>(r);
    RankCost rc;
    rc.owned = d.owned[k];
    rc.ghosts = g.ghosts[k].size();
    rc.neighbours = g.sources[k].size();
    rc.bytes = static_cast<double>(rc.ghosts * kGhostBytesPerStep);
    rc.compute = total_weight > 0.0 ? rank_work[k] / total_weight * c.step_serial : 0.0;
    if (pairs != nullptr && pairs->total > 0) {
      rc.across = pairs->across[k];
      const double again = 0.5 * static_cast<double>(rc.across);
      rc.compute += again / static_cast<double>(pairs->total) * c.step_serial;
      c.duplicated += again / static_cast<double>(pairs->total);
    }
    rc.comm = static_cast<double>(rc.neighbours) * net.latency + rc.bytes / net.bandwidth;
    c.step_compute = std::max(c.step_compute, rc.compute);
    c.step_comm = std::max(c.step_comm, rc.comm);
    c.ranks.push_back(rc);
  }
  return c;
}

}  // namespace drumlab
