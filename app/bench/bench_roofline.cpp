#include "app/bench/bench_roofline.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <ostream>
#include <string_view>

#include <fmt/format.h>

#include "app/bench/machine_limits.hpp"
#include "app/bench/roofline_model.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/search/verlet_list.hpp"
#include "engine/session/phase_meter.hpp"
#include "engine/simulation.hpp"
#include "engine/threads.hpp"

namespace drumlab::bench {

namespace {

struct Measured {
  PhaseStats phase;
  RunCounts counts;
  LawShape shape;
  std::string method;
};

const VerletListSearch* verlet_list(const Simulation& sim) {
  return dynamic_cast<const VerletListSearch*>(&sim.search());
}

Measured measure(const RollingState& rolling, const RooflineOptions& opt) {
  set_thread_count(opt.threads);
  SimulationState state = rolling.state;
  if (!opt.method.empty()) state.search_method = opt.method;
  Simulation sim(rolling.scene, std::move(state));
  warm_up(sim, opt.warmup);
  Measured m;
  m.method = std::string(sim.search().name());
  m.shape = law_shape(rolling.scene, sim.particles());
  m.counts = count_run(sim, opt.steps, &m.phase);
  if (!m.shape.cohesive) m.counts.cohesive_pairs_per_step = 0.0;
  return m;
}

}  // namespace

RunCounts count_run(Simulation& sim, std::uint64_t steps, PhaseStats* phase) {
  RunCounts c;
  c.verlet = verlet_list(sim) != nullptr;
  const auto rebuilds = [&] { return c.verlet ? verlet_list(sim)->rebuilds() : 0; };
  const auto patches = [&] { return c.verlet ? verlet_list(sim)->patches() : 0; };
  const std::uint64_t rebuilds0 = rebuilds();
  const std::uint64_t patches0 = patches();
  PhaseMeter meter(sim);
  constexpr int kSamples = 5;
  for (int k = 0; k < kSamples; ++k) {
    c.cohesive_pairs_per_step += static_cast<double>(sim.diagnostics().bridges) / kSamples;
    const std::uint64_t done = steps * static_cast<std::uint64_t>(k) / kSamples;
    sim.advance(steps * static_cast<std::uint64_t>(k + 1) / kSamples - done);
  }
  const PhaseStats p = meter.finish();
  c.work = p.work;
  c.steps = p.steps;
  c.pairs_tested = p.search.pairs_tested;
  c.builds = c.verlet ? rebuilds() - rebuilds0 : p.steps;
  c.patches = patches() - patches0;
  if (phase != nullptr) *phase = p;
  return c;
}

namespace {

struct Row {
  std::string phase;
  double seconds = 0.0;
  Work work;
  std::string level;  ///< where the streamed bytes come from
  double gflops = 0.0, divsqrt_g = 0.0, gbs = 0.0;
  double share_flops = 0.0, share_divsqrt = 0.0, share_bw = 0.0, share_gather = 0.0;
  std::string bound;
};

/// Rates, their shares of the roofs and the bound: the roof a phase is closest to; "latency"
/// when it reaches under a fifth of every roof (dependent operations, branches, waiting on
/// scattered loads).
Row classify(std::string phase, double seconds, const Work& w, double working_set,
             const MachineLimits& lim, int threads) {
  Row r;
  r.phase = std::move(phase);
  r.seconds = seconds;
  r.work = w;
  const BandwidthLevel& level = lim.level_for(working_set);
  r.level = level.name;
  const double t = std::max(seconds, 1e-12);
  const double cores = static_cast<double>(threads);
  const double bw = level.gbs * (level.name == "memory" ? 1.0 : cores);
  r.gflops = w.flops / t * 1e-9;
  r.divsqrt_g = w.divsqrt / t * 1e-9;
  r.gbs = w.stream / t * 1e-9;
  r.share_flops = r.gflops / (lim.peak_gflops * cores);
  r.share_divsqrt = r.divsqrt_g / (lim.divsqrt_per_s * 1e-9 * cores);
  r.share_bw = r.gbs / bw;
  r.share_gather = w.gather / t * 1e-9 / (lim.levels.front().gbs * cores);
  const std::array<std::pair<double, std::string_view>, 4> roofs = {
      {{r.share_flops, "compute (FMA)"},
       {r.share_divsqrt, "divide/sqrt"},
       {r.share_bw, "bandwidth"},
       {r.share_gather, "L1 gathers"}}};
  const auto top = *std::max_element(roofs.begin(), roofs.end());
  r.bound = top.first >= 0.2
                ? fmt::format("{} {:.0f} %", top.second, 100.0 * top.first)
                : fmt::format("latency (nearest: {} {:.0f} %)", top.second, 100.0 * top.first);
  if (top.second == "bandwidth" && top.first >= 0.2) r.bound += " of " + r.level;
  return r;
}

void print_limits(const MachineLimits& lim) {
  fmt::print("machine, one core: peak {:.1f} GFLOP/s ({})", lim.peak_gflops, lim.isa);
  if (lim.peak_gflops_512 > 0.0) {
    fmt::print(", {:.1f} with AVX-512 (not used by this build)", lim.peak_gflops_512);
  }
  fmt::print("; {:.2f} G divisions + square roots/s\n", lim.divsqrt_per_s * 1e-9);
  fmt::print("bandwidth, one core (STREAM triad):");
  for (const BandwidthLevel& l : lim.levels) {
    fmt::print(" {} ({:.3g} MiB) {:.1f} GB/s;", l.name, static_cast<double>(l.bytes) / (1 << 20),
               l.gbs);
  }
  fmt::print("\n");
}

void print_rows(const std::vector<Row>& rows, double particle_steps) {
  fmt::print("{:<12} {:>6} {:>9} {:>9} {:>8} {:>9} {:>9} {:>7} {:>7} {:>7} {:>7} {:>6}  {}\n",
             "phase", "time%", "ns/p-st", "flop/p-st", "dvsq/p-st", "B/p-st", "GFLOP/s", "%peak",
             "%dvsq", "GB/s", "%bw", "from", "bound");
  const double total = rows.back().seconds;
  for (const Row& r : rows) {
    fmt::print(
        "{:<12} {:>6.1f} {:>9.1f} {:>9.0f} {:>8.1f} {:>9.0f} {:>9.2f} {:>7.1f} {:>7.1f} {:>7.1f} "
        "{:>7.1f} {:>6}  {}\n",
        r.phase, 100.0 * r.seconds / total, 1e9 * r.seconds / particle_steps,
        r.work.flops / particle_steps, r.work.divsqrt / particle_steps,
        (r.work.stream + r.work.gather) / particle_steps, r.gflops, 100.0 * r.share_flops,
        100.0 * r.share_divsqrt, r.gbs, 100.0 * r.share_bw, r.level, r.bound);
  }
}

void write_csv(const std::filesystem::path& file, const std::string& scene, const Measured& m,
               const std::vector<Row>& rows, double particle_steps, int threads) {
  std::string text =
      "scene,method,threads,phase,seconds,ns_per_particle_step,flops_per_particle_step,"
      "divsqrt_per_particle_step,stream_bytes_per_particle_step,gather_bytes_per_particle_step,"
      "gflops,share_of_peak,share_of_divsqrt,gbs,level,share_of_bandwidth,bound\n";
  for (const Row& r : rows) {
    text += fmt::format(
        "{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.4g},"
        "{:.4g},{:.6g},{},{:.4g},\"{}\"\n",
        scene, m.method, threads, r.phase, r.seconds, 1e9 * r.seconds / particle_steps,
        r.work.flops / particle_steps, r.work.divsqrt / particle_steps,
        r.work.stream / particle_steps, r.work.gather / particle_steps, r.gflops, r.share_flops,
        r.share_divsqrt, r.gbs, r.level, r.share_bw, r.bound);
  }
  write_file_atomically(file, [&](std::ostream& out) { out << text; });
}

}  // namespace

void run_bench_roofline(const RooflineOptions& opt) {
  make_output_dir(opt.out);
  const RollingState rolling = rolling_state(opt.scene, opt.plan);
  const Measured m = measure(rolling, opt);
  const MachineLimits lim = measure_machine_limits(opt.quick);
  print_limits(lim);
  const PhaseWork pw = phase_work(m.shape, m.counts);
  const StepTimers& t = m.phase.timers;
  const double particle_steps = std::max(1.0, static_cast<double>(m.phase.work.particles));
  std::vector<Row> rows = {
      classify("search", t.search, pw.search, pw.working_set_particles, lim, opt.threads),
      classify("pair forces", t.forces, pw.forces, pw.working_set_forces, lim, opt.threads),
      classify("walls", t.walls, pw.walls, 0.0, lim, opt.threads),
      classify("integration", t.integration, pw.integration, pw.working_set_forces, lim,
               opt.threads),
      classify("re-ordering", t.reorder, pw.reorder, 2.0 * pw.working_set_particles, lim,
               opt.threads)};
  Work all;
  for (const Row& r : rows) all += r.work;
  rows.push_back(classify("step", t.total(), all, pw.working_set_forces, lim, opt.threads));
  fmt::print("{}: {} particles, {}, {} thread(s), {} steps: {:.4g} particle-steps/s\n",
             rolling.scene.name, m.phase.work.particles / std::max<std::uint64_t>(1, m.phase.steps),
             m.method, opt.threads, m.phase.steps, particle_steps / std::max(t.total(), 1e-12));
  fmt::print(
      "per step: {:.0f} listed pairs, {:.0f} touching, {:.0f} wall candidates, {:.0f} wall "
      "contacts, {:.0f} live bridges; {} search builds, {} list patches, {} re-orderings\n",
      static_cast<double>(m.counts.work.listed_pairs) / m.counts.steps,
      static_cast<double>(m.counts.work.touching_pairs) / m.counts.steps,
      static_cast<double>(m.counts.work.wall_candidates) / m.counts.steps,
      static_cast<double>(m.counts.work.wall_contacts) / m.counts.steps,
      m.counts.cohesive_pairs_per_step, m.counts.builds, m.counts.patches, m.counts.work.reorders);
  print_rows(rows, particle_steps);
  const auto file = std::filesystem::path(opt.out) / ("roofline_" + rolling.scene.name + ".csv");
  write_csv(file, rolling.scene.name, m, rows, particle_steps, opt.threads);
  fmt::print("wrote {}\n", file.string());
}

}  // namespace drumlab::bench
