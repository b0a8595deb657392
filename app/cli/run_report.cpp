#include "app/cli/run_report.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "engine/openmp_waiting.hpp"
#include "engine/threads.hpp"

namespace drumlab::cli {

ProgressBar::ProgressBar(std::string label, std::uint64_t total_steps)
    : label_(std::move(label)),
      total_(total_steps),
      tty_(::isatty(::fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(std::uint64_t done) {
  if (!tty_ || total_ == 0) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
  const int width = 30;
  const int filled =
      static_cast<int>(width * static_cast<double>(done) / static_cast<double>(total_));
  fmt::print(stderr, "\r{:<8} [{:<{}}] {:5.1f}%  {:8.0f} steps/s  ETA {:4.0f} s ", label_,
             std::string(static_cast<std::size_t>(filled), '='), width,
             100.0 * static_cast<double>(done) / static_cast<double>(total_), rate, eta);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (tty_ && total_ > 0) fmt::print(stderr, "\n");
}

void print_summary(const Simulation& sim, const PhaseStats& phase) {
  const double n = static_cast<double>(sim.particles().size());
  const double steps = static_cast<double>(std::max<std::uint64_t>(phase.steps, 1));
  const double particle_steps = n * static_cast<double>(phase.steps);
  const double total = std::max(phase.timers.total(), 1e-12);
  const Diagnostics d = sim.diagnostics();
  auto share = [&](double t) { return 100.0 * t / total; };
  fmt::print("particles         {}\n", sim.particles().size());
  fmt::print(
      "steps             {} (dt = {:.4g} s = {:.3g} Rayleigh times), simulated {:.4g} s, t = "
      "{:.4g} s\n",
      phase.steps, sim.dt(), sim.dt() / sim.rayleigh_time(),
      static_cast<double>(phase.steps) * sim.dt(), sim.time());
  fmt::print("search method     {} ({})\n", sim.search().name(), sim.search().description());
#ifdef _OPENMP
  fmt::print("threads           {} (OpenMP: pair forces, walls, integration); waiting: {}\n",
             max_threads(), openmp_waiting_description());
#endif
  const double stepping = phase.wall_seconds - phase.output_seconds;
  fmt::print("wall time         {:.3f} s (stepping {:.3f} s, output {:.3f} s)\n",
             phase.wall_seconds, stepping, phase.output_seconds);
  fmt::print("throughput        {:.4g} particle-steps/s (stepping only)\n",
             stepping > 0 ? particle_steps / stepping : 0.0);
  fmt::print(
      "time split        search {:.1f} %, forces {:.1f} %, walls {:.1f} %, integration {:.1f} %, "
      "re-ordering {:.1f} %\n",
      share(phase.timers.search), share(phase.timers.forces), share(phase.timers.walls),
      share(phase.timers.integration), share(phase.timers.reorder));
  fmt::print(
      "search / particle cells visited {:.2f}, pairs tested {:.2f}, contacts {:.3f}, tested per "
      "contact {:.2f}\n",
      static_cast<double>(phase.search.cells_visited) / (n * steps),
      static_cast<double>(phase.search.pairs_tested) / (n * steps),
      2.0 * static_cast<double>(phase.search.pairs_found) / (n * steps),
      phase.search.pairs_found > 0 ? static_cast<double>(phase.search.pairs_tested) /
                                         static_cast<double>(phase.search.pairs_found)
                                   : 0.0);
  if (const std::string extra = sim.search().report(); !extra.empty()) {
    fmt::print("search detail     {}\n", extra);
  }
  fmt::print(
      "energy            kinetic {:.5g} J, rotational {:.5g} J, potential {:.5g} J, elastic {:.5g} "
      "J\n",
      d.kinetic_energy, d.rotational_energy, d.potential_energy, d.elastic_energy);
  fmt::print(
      "health            max overlap/radius {:.4f}, outside drum {}, non-finite {}, contacts {} + "
      "{} wall\n",
      d.max_overlap_ratio, d.outside_drum, d.non_finite, d.contacts, d.wall_contacts);
}

void settle_with_progress(RunSession& session, std::uint64_t steps) {
  if (steps == 0) return;
  ProgressBar bar("settle", steps);
  session.settle([&](std::uint64_t done, std::uint64_t) {
    bar.update(done);
    return true;
  });
  bar.finish();
}

}  // namespace drumlab::cli
