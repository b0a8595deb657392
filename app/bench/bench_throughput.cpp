#include "app/bench/bench_throughput.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/run/run_report.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/search/verlet_list.hpp"
#include "engine/simulation.hpp"
#include "engine/threads.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/bench_chart.hpp"
#endif

namespace drumlab::bench {

namespace {

struct ThroughputRow {
  std::string method;
  std::string label;  ///< method, with the sort interval when several are compared
  std::uint64_t sort_every = 0;
  int threads = 1;
  std::size_t particles = 0;
  PhaseStats phase;
  std::uint64_t rebuilds = 0;  ///< Verlet rebuilds in the timed steps (0 for other methods)
  std::uint64_t patches = 0;   ///< Verlet patches (the list mended, not rebuilt) in the timed steps
  double heap_bytes_per_particle = 0.0;
  double speedup = 1.0;  ///< against the same method with 1 thread

  double stepping() const { return phase.wall_seconds; }
  double rate() const {
    const double s = stepping();
    return s > 0.0 ? static_cast<double>(particles) * static_cast<double>(phase.steps) / s : 0.0;
  }
  /// Particle-steps per second of process CPU time (all threads): with N threads, below the
  /// 1-thread rate by the cost of parallel work and of threads waiting at barriers.
  double cpu_rate() const {
    return phase.cpu_seconds > 0.0 ? static_cast<double>(particles) *
                                         static_cast<double>(phase.steps) / phase.cpu_seconds
                                   : 0.0;
  }
  double share(double t) const {
    const double total = phase.timers.total();
    return total > 0.0 ? t / total : 0.0;
  }
  double per_particle_step(std::uint64_t v) const {
    const double n = static_cast<double>(particles) * static_cast<double>(phase.steps);
    return n > 0.0 ? static_cast<double>(v) / n : 0.0;
  }
  double tested_per_contact() const {
    // No contacts (a loose fill): no ratio.
    return phase.search.pairs_found > 0 ? static_cast<double>(phase.search.pairs_tested) /
                                              static_cast<double>(phase.search.pairs_found)
                                        : std::numeric_limits<double>::quiet_NaN();
  }
};

struct ListUpkeep {
  std::uint64_t rebuilds = 0;
  std::uint64_t patches = 0;
};

ListUpkeep verlet_upkeep(const Simulation& sim) {
  const auto* v = dynamic_cast<const VerletListSearch*>(&sim.search());
  return v != nullptr ? ListUpkeep{v->rebuilds(), v->patches()} : ListUpkeep{};
}

ThroughputRow measure(const RollingState& rolling, const std::string& method,
                      std::uint64_t sort_every, int threads, std::uint64_t steps,
                      std::uint64_t warmup, bool dry) {
  set_thread_count(threads);
  if (threads > max_threads()) {
    fmt::print("note: built without OpenMP: {} threads asked, 1 runs\n", threads);
  }
  ThroughputRow row;
  row.method = method;
  row.sort_every = sort_every;
  row.threads = threads;
  SceneConfig scene = rolling.scene;
  scene.performance.sort_every = sort_every;
  const std::size_t heap0 = heap_bytes_in_use();
  {
    SimulationState state = rolling.state;  // counted: the copy becomes the simulation's
    state.search_method = method;
    if (dry) {  // the same particles without the cohesive laws and their state
      scene.liquid.enabled = false;
      scene.cohesion.enabled = false;
      state.contact_state_size = 0;
      state.contact_state.clear();
      state.particles.extra.clear();
    }
    Simulation sim(scene, std::move(state));
    row.particles = sim.particles().size();
    warm_up(sim, warmup);
    const ListUpkeep upkeep0 = verlet_upkeep(sim);
    PhaseMeter meter(sim);
    sim.advance(steps);
    row.phase = meter.finish();
    const ListUpkeep upkeep1 = verlet_upkeep(sim);
    row.rebuilds = upkeep1.rebuilds - upkeep0.rebuilds;
    row.patches = upkeep1.patches - upkeep0.patches;
    const std::size_t heap1 = heap_bytes_in_use();
    row.heap_bytes_per_particle =
        row.particles > 0 && heap1 > heap0
            ? static_cast<double>(heap1 - heap0) / static_cast<double>(row.particles)
            : 0.0;
  }
  return row;
}

std::string optional_number(double v) {
  return std::isfinite(v) ? fmt::format("{:.4g}", v) : std::string();
}

void print_row(const ThroughputRow& r) {
  fmt::print(
      "{:<20} {:>3} {:>6} {:>12.4g} {:>10.4g} {:>7.2f} {:>7.1f} {:>7.1f} {:>7.1f} {:>7.1f} "
      "{:>8.2f} "
      "{:>8} {:>8} {:>8} {:>8.0f}\n",
      r.label, r.threads, r.phase.steps, r.rate(), r.cpu_rate(), r.speedup,
      100.0 * r.share(r.phase.timers.search), 100.0 * r.share(r.phase.timers.forces),
      100.0 * r.share(r.phase.timers.walls),
      100.0 * r.share(r.phase.timers.integration + r.phase.timers.reorder),
      r.per_particle_step(r.phase.search.pairs_tested),
      std::isfinite(r.tested_per_contact()) ? fmt::format("{:.2f}", r.tested_per_contact()) : "-",
      r.rebuilds, r.patches, r.heap_bytes_per_particle);
}

void write_csv(const std::filesystem::path& file, const std::string& scene,
               const std::vector<ThroughputRow>& rows) {
  write_file_atomically(file, [&](std::ostream& os) {
    os << "scene,method,sort_every,threads,particles,steps,stepping_s,particle_steps_per_s,"
          "particle_steps_per_cpu_s,speedup,"
          "search_share,forces_share,walls_share,integration_share,cells_per_particle,"
          "tested_per_particle,contacts_per_particle,tested_per_contact,verlet_rebuilds,"
          "verlet_patches,heap_bytes_per_particle\n";
    for (const ThroughputRow& r : rows) {
      const auto& t = r.phase.timers;
      os << fmt::format(
          "{},{},{},{},{},{},{:.6g},{:.6g},{:.6g},{:.4g},{:.4f},{:.4f},{:.4f},{:.4f},{:.4g},"
          "{:.4g},{:.4g},{},{},{},{:.1f}\n",
          scene, r.method, r.sort_every, r.threads, r.particles, r.phase.steps, r.stepping(),
          r.rate(), r.cpu_rate(), r.speedup, r.share(t.search), r.share(t.forces), r.share(t.walls),
          r.share(t.integration + t.reorder), r.per_particle_step(r.phase.search.cells_visited),
          r.per_particle_step(r.phase.search.pairs_tested),
          2.0 * r.per_particle_step(r.phase.search.pairs_found),
          optional_number(r.tested_per_contact()), r.rebuilds, r.patches,
          r.heap_bytes_per_particle);
    }
  });
}

void write_chart(const std::filesystem::path& file, const std::string& scene,
                 const std::vector<std::string>& methods, const std::vector<int>& threads,
                 const std::vector<ThroughputRow>& rows) {
#ifdef DRUMLAB_WITH_RENDER
  render::BarPanel rate{fmt::format("{}: throughput (stepping only)", scene),
                        "million particle-steps / s",
                        methods,
                        {},
                        false};
  render::BarPanel share{"search share of the step time", "%", methods, {}, false};
  for (const int t : threads) {
    render::BarSeries r{fmt::format("{} thread{}", t, t > 1 ? "s" : ""), {}};
    render::BarSeries s = r;
    for (const std::string& m : methods) {
      const auto it = std::find_if(rows.begin(), rows.end(),
                                   [&](auto& x) { return x.label == m && x.threads == t; });
      r.values.push_back(it->rate() * 1e-6);
      s.values.push_back(100.0 * it->share(it->phase.timers.search));
    }
    rate.series.push_back(std::move(r));
    share.series.push_back(std::move(s));
  }
  render::write_bar_charts({rate, share}, file);
  fmt::print("wrote {}\n", file.string());
#else
  (void)scene, (void)methods, (void)threads, (void)rows;
  fmt::print("note: built without rendering: no chart {}\n", file.string());
#endif
}

std::vector<std::string> default_methods() {
  std::vector<std::string> m = search_method_names();
  m.erase(std::remove(m.begin(), m.end(), "brute"), m.end());
  return m;
}

}  // namespace

void run_bench_throughput(const ThroughputOptions& opt) {
  const std::vector<std::string> methods = opt.methods.empty() ? default_methods() : opt.methods;
  for (const std::string& m : methods) (void)make_search(m);  // unknown names: exit 2 up front
  const std::filesystem::path out = opt.out;
  make_output_dir(out);
  const RollingState rolling = rolling_state(opt.scene, opt.plan);
  const std::string& name = rolling.scene.name;
  fmt::print("scene             {} ({}), {} particles\n", name, opt.scene,
             rolling.state.particles.size());
  fmt::print("state             {}\n", rolling.origin);
#if defined(DRUMLAB_AVX512_BUILD)
  fmt::print("build             AVX-512 (-march=x86-64-v4; cmake -DDRUMLAB_AVX512=OFF: AVX2)\n");
#elif defined(DRUMLAB_AVX2_BUILD)
  fmt::print("build             AVX2 + FMA (-march=x86-64-v3; cmake -DDRUMLAB_AVX2=OFF: SSE2)\n");
#else
  fmt::print("build             x86-64 baseline (SSE2), no AVX2/FMA\n");
#endif
  fmt::print(
      "run               {} warm-up steps (and a re-ordering, unless sort_every = 0) + {} "
      "timed steps per method{}\n",
      opt.warmup, opt.steps,
      std::find(methods.begin(), methods.end(), "brute") != methods.end()
          ? fmt::format(" (brute: at most {})", kBruteMaxSteps)
          : std::string());
  std::vector<int> threads{1};
  if (opt.threads > 1) threads.push_back(opt.threads);
  std::vector<std::uint64_t> sorts;
  for (const std::int64_t k : opt.sort_every) sorts.push_back(static_cast<std::uint64_t>(k));
  if (sorts.empty()) sorts.push_back(rolling.scene.performance.sort_every);
  fmt::print("re-ordering       every {} steps (performance.sort_every; 0: never){}\n",
             fmt::join(sorts, " / "),
             opt.repeats > 1 ? fmt::format(", fastest of {} runs per row", opt.repeats) : "");
  fmt::print(
      "{:<20} {:>3} {:>6} {:>12} {:>10} {:>7} {:>7} {:>7} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} "
      "{:>8}\n",
      "method", "thr", "steps", "p-steps/s", "per cpu-s", "speedup", "search%", "forces%", "walls%",
      "integr%", "tested/p", "tst/cont", "rebuilds", "patches", "heap B/p");
  std::vector<ThroughputRow> rows;
  std::vector<std::string> labels;
  const bool cohesive = rolling.scene.liquid.enabled || rolling.scene.cohesion.enabled;
  std::vector<bool> dry_runs{false};
  if (opt.dry_too && cohesive) dry_runs.push_back(true);
  for (const std::string& m : methods) {
    const std::uint64_t steps = m == "brute" ? std::min(opt.steps, kBruteMaxSteps) : opt.steps;
    for (const std::uint64_t k : sorts) {
      // The thread counts, and with --dry-too the wet and the dry run, take turns within each
      // repeat, so that a speed-up or the wet/dry ratio compares runs made in the same minutes of
      // a machine whose speed drifts.
      std::vector<std::vector<ThroughputRow>> best(dry_runs.size(),
                                                   std::vector<ThroughputRow>(threads.size()));
      for (int rep = 0; rep < std::max(1, opt.repeats); ++rep) {
        for (std::size_t v = 0; v < dry_runs.size(); ++v) {
          for (std::size_t q = 0; q < threads.size(); ++q) {
            ThroughputRow run = measure(rolling, m, k, threads[q], steps,
                                        m == "brute" ? 1 : opt.warmup, dry_runs[v]);
            if (rep == 0 || run.rate() > best[v][q].rate()) best[v][q] = std::move(run);
          }
        }
      }
      for (std::size_t v = 0; v < dry_runs.size(); ++v) {
        std::string label = sorts.size() > 1 ? fmt::format("{} sort {}", m, k) : m;
        if (dry_runs[v]) label += " dry";
        labels.push_back(label);
        const double base_rate = best[v].front().rate();
        for (ThroughputRow& row : best[v]) {
          row.label = label;
          row.speedup = base_rate > 0.0 ? row.rate() / base_rate : 0.0;
          print_row(row);
          std::fflush(stdout);  // rows as they come, also into a pipe or file
          rows.push_back(std::move(row));
        }
        if (dry_runs[v]) {
          const ThroughputRow& wet = rows[rows.size() - 2 * threads.size()];
          fmt::print("{:<20} wet costs {:.3f}x dry per particle-step (1 thread)\n", "",
                     rows[rows.size() - threads.size()].rate() / wet.rate());
        }
      }
    }
  }
  fmt::print(
      "heap B/p: bytes the allocator holds after the run minus before the state was copied, per "
      "particle (glibc mallinfo2); peak RSS of this process {:.1f} MiB\n",
      static_cast<double>(peak_rss_bytes()) / (1024.0 * 1024.0));
  const ThroughputRow* best = nullptr;
  for (const ThroughputRow& r : rows) {
    if (r.threads == 1 && (best == nullptr || r.rate() > best->rate())) best = &r;
  }
  if (best != nullptr) {
    fmt::print(
        "fastest (1 thread) {}: {:.4g} particle-steps/s ({:.4g} per CPU second), search {:.1f} % "
        "of the step\n",
        best->label, best->rate(), best->cpu_rate(),
        100.0 * best->share(best->phase.timers.search));
  }
  const auto csv = out / fmt::format("throughput_{}.csv", name);
  write_csv(csv, name, rows);
  fmt::print("wrote {}\n", csv.string());
  write_chart(out / fmt::format("throughput_{}.png", name), name, labels, threads, rows);
}

}  // namespace drumlab::bench
