#include "engine/parallel/exchange_cost.hpp"

#include <algorithm>

namespace drumlab {

DecompositionCost decomposition_cost(const Decomposition& d, const GhostLayer& g, double rate,
                                     const NetworkModel& net, std::span<const double> rank_work) {
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
    rc.comm = static_cast<double>(rc.neighbours) * net.latency + rc.bytes / net.bandwidth;
    c.step_compute = std::max(c.step_compute, rc.compute);
    c.step_comm = std::max(c.step_comm, rc.comm);
    c.ranks.push_back(rc);
  }
  return c;
}

}  // namespace drumlab
