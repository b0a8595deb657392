#include "app/mpi/mpi_report.hpp"

#include <fmt/format.h>

#include "engine/openmp_waiting.hpp"

namespace drumlab::mpi {

void reduce_phase(MpiDomain& domain, PhaseStats& phase) {
  const double ranks = static_cast<double>(domain.comm().size());
  for (double* mean : {&phase.timers.search, &phase.timers.forces, &phase.timers.walls,
                       &phase.timers.integration, &phase.timers.reorder, &phase.timers.spray}) {
    *mean = domain.sum(*mean) / ranks;
  }
  for (std::uint64_t* sum :
       {&phase.search.cells_visited, &phase.search.pairs_tested, &phase.search.pairs_found}) {
    *sum = domain.sum(*sum);
  }
  phase.wall_seconds = domain.max(phase.wall_seconds);
  phase.cpu_seconds = domain.max(phase.cpu_seconds);
  phase.output_seconds = domain.max(phase.output_seconds);
}

void print_decomposition(const MpiRunSummary& s) {
  const MpiBalance& b = s.balance;
  fmt::print("ranks             {} x {} thread(s); waiting threads: {}\n", s.ranks, s.threads,
             openmp_waiting_description());
  fmt::print("owned per rank    min {} / mean {:.1f} / max {} (max/mean {:.3f})\n", b.owned_min,
             b.owned_mean, b.owned_max, b.owned_mean > 0 ? b.owned_max / b.owned_mean : 0.0);
  fmt::print(
      "communication     {:.1f} % of the time inside MPI (mean over ranks; max {:.1f} %), "
      "{} exchanges ({:.2f} s, slowest rank), {} re-balances ({:.3f} s finding the cuts)\n",
      100.0 * s.comm_share_mean, 100.0 * s.comm_share_max, b.exchanges, s.exchange_seconds,
      b.rebalances, s.recut_seconds);
  if (s.ranks > 1 && s.rebalance_every > 0) {
    if (s.balance_by == BalanceBy::count) {
      fmt::print("balance           by count, re-cut every {} steps\n", s.rebalance_every);
    } else if (b.first_imbalance > 0.0) {
      fmt::print(
          "balance           by time, checked every {} steps, re-cut above +{:.0f} %; slowest "
          "rank's work / mean: {:.3f} at the first check, {:.3f} at the last\n",
          s.rebalance_every, 100.0 * s.balance_threshold, b.first_imbalance, b.last_imbalance);
    } else {
      fmt::print("balance           by time, checked every {} steps (no check in this run)\n",
                 s.rebalance_every);
    }
  }
  fmt::print("ghosts            at the exchanges {} sent in full (new), {} kept (motion only)\n",
             b.ghosts_new, b.ghosts_kept);
  if (s.wet && s.ranks > 1) {
    fmt::print("bridge events     {} (liquid bridges formed or ruptured), replayed on every rank\n",
               b.bridge_events);
  }
  const OutputTimes& o = s.output;
  if (o.checkpoints + o.frames > 0) {
    fmt::print("output            {} checkpoint(s) in {:.3f} s, {} series frame(s) in {:.3f} s\n",
               o.checkpoints, o.checkpoint_seconds, o.frames, o.frame_seconds);
  }
}

}  // namespace drumlab::mpi
