#include "app/bench/bench_search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "app/bench/paper_reference.hpp"
#include "app/run/run_report.hpp"
#include "engine/fill/paper_packing.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/search/contact_search.hpp"
#include "engine/search/verlet_list.hpp"
#include "engine/simulation.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/bench_chart.hpp"
#endif

namespace drumlab::bench {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Particles to search: a flowing state or a paper packing.
struct Dataset {
  std::string name;
  std::vector<Vec3> position;
  std::vector<double> radius;
  std::optional<Box> domain;
  std::optional<double> period_z;
  const PaperTable* paper = nullptr;  ///< the paper's estimates to print beside ours
  bool brute = false;                 ///< small enough for O(N^2)
};

struct SearchRow {
  std::string dataset, method;
  std::size_t particles = 0;
  double contacts_pp = 0, cells_pp = 0, tested_pp = 0, tested_per_contact = 0;
  double first_s = 0;              ///< first call on a fresh search object
  double call_s = 0;               ///< median of the repeated calls on the same positions
  double build_s = kNaN;           ///< building the grid (Verlet: the first call's list build)
  double visit_s = kNaN;           ///< visiting candidates (Verlet: re-testing the list)
  double step_s = kNaN;            ///< seconds per step of a short dynamic run
  double search_share = kNaN;      ///< search / step time in that run
  double paper_operations = kNaN;  ///< the paper's operations per particle
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

SearchRow measure_search(const Dataset& d, const std::string& method, int repeats) {
  SearchRow row;
  row.dataset = d.name;
  row.method = method;
  row.particles = d.position.size();
  auto search = make_search(method);
  const SearchInput in{d.position, d.radius, 0.0, d.domain, d.period_z};
  std::vector<IndexPair> pairs;
  auto t0 = std::chrono::steady_clock::now();
  search->find_pairs(in, pairs);
  row.first_s = seconds_since(t0);
  const SearchTimings first = search->timings();
  std::vector<double> times, builds, visits;
  for (int k = 0; k < std::max(1, repeats); ++k) {
    t0 = std::chrono::steady_clock::now();
    search->find_pairs(in, pairs);
    times.push_back(seconds_since(t0));
    builds.push_back(search->timings().build);
    visits.push_back(search->timings().visit);
  }
  const auto median = [](std::vector<double>& v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  row.call_s = median(times);
  // The engine's own split of each call: grid build and candidate visits.
  row.build_s = median(builds);
  row.visit_s = median(visits);
  // Counters of the last call: for a Verlet list the steady state (list re-tested, no rebuild).
  const SearchCounters& c = search->counters();
  const double n = std::max<double>(1.0, static_cast<double>(row.particles));
  row.cells_pp = static_cast<double>(c.cells_visited) / n;
  row.tested_pp = static_cast<double>(c.pairs_tested) / n;
  row.contacts_pp = 2.0 * static_cast<double>(pairs.size()) / n;
  row.tested_per_contact =
      pairs.empty() ? kNaN
                    : static_cast<double>(c.pairs_tested) / static_cast<double>(pairs.size());
  if (dynamic_cast<const VerletListSearch*>(search.get()) != nullptr) {
    row.build_s = first.build;  // the first call builds the list; later ones only re-test it
  }
  if (d.paper != nullptr && method.size() == 2 && method[0] == 'm') {
    row.paper_operations =
        d.paper->methods.at(static_cast<std::size_t>(method[1] - '1')).operations_per_particle;
  }
  return row;
}

/// Seconds per step and the search share of a short run from the rolling state.
void measure_steps(const RollingState& rolling, SearchRow& row, std::uint64_t steps) {
  if (steps == 0) return;
  SimulationState state = rolling.state;
  state.search_method = row.method;
  Simulation sim(rolling.scene, std::move(state));
  sim.advance(std::min<std::uint64_t>(5, steps));
  PhaseMeter meter(sim);
  sim.advance(steps);
  const PhaseStats s = meter.finish();
  row.step_s = s.wall_seconds / static_cast<double>(s.steps);
  row.search_share = s.timers.total() > 0.0 ? s.timers.search / s.timers.total() : kNaN;
}

Dataset paper_dataset(int table) {
  const PaperTable& ref = kPaperTables.at(static_cast<std::size_t>(table - 1));
  const Vec3 box(1.85, 1.80, ref.depth);
  Particles p = paper_packing(box, 2500.0);
  return {fmt::format("paper_table{}", table),
          std::move(p.position),
          std::move(p.radius),
          Box{Vec3::Zero(), box},
          std::nullopt,
          &ref,
          false};
}

std::string cell(double v, const char* format = "{:.3g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string("-");
}

void print_row(const SearchRow& r) {
  const double n = static_cast<double>(r.particles);
  fmt::print("{:<20} {:<14} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9} {:>7} {:>9}\n",
             r.dataset, r.method, cell(r.cells_pp), cell(r.tested_pp), cell(r.tested_per_contact),
             cell(1e9 * r.call_s / n, "{:.1f}"), cell(1e9 * r.build_s / n, "{:.1f}"),
             cell(1e9 * r.visit_s / n, "{:.1f}"), cell(1e9 * r.step_s / n, "{:.1f}"),
             cell(r.cells_pp + r.tested_pp, "{:.0f}"), cell(100.0 * r.search_share, "{:.1f}"),
             cell(r.paper_operations, "{:.0f}"));
}

void write_csv(const std::filesystem::path& file, const std::vector<SearchRow>& rows) {
  auto v = [](double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : std::string(); };
  write_file_atomically(file, [&](std::ostream& os) {
    os << "dataset,method,particles,contacts_per_particle,cells_per_particle,tested_per_particle,"
          "tested_per_contact,first_call_s,call_s,build_s,visit_s,step_s,search_share,"
          "paper_operations_per_particle\n";
    for (const SearchRow& r : rows) {
      os << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.dataset, r.method,
                        r.particles, v(r.contacts_pp), v(r.cells_pp), v(r.tested_pp),
                        v(r.tested_per_contact), v(r.first_s), v(r.call_s), v(r.build_s),
                        v(r.visit_s), v(r.step_s), v(r.search_share), v(r.paper_operations));
    }
  });
}

void write_chart(const std::filesystem::path& file, const std::vector<std::string>& datasets,
                 const std::vector<std::string>& methods, const std::vector<SearchRow>& rows) {
#ifdef DRUMLAB_WITH_RENDER
  render::BarPanel tested{
      "pairs tested per true contact", "tested / contact (log)", methods, {}, true};
  render::BarPanel time{"search time per particle and call", "ns (log)", methods, {}, true};
  for (const std::string& d : datasets) {
    render::BarSeries t{d, {}}, s{d, {}};
    for (const std::string& m : methods) {
      const auto it = std::find_if(rows.begin(), rows.end(),
                                   [&](auto& r) { return r.dataset == d && r.method == m; });
      t.values.push_back(it == rows.end() ? kNaN : it->tested_per_contact);
      s.values.push_back(it == rows.end() ? kNaN
                                          : 1e9 * it->call_s / static_cast<double>(it->particles));
    }
    tested.series.push_back(std::move(t));
    time.series.push_back(std::move(s));
  }
  render::write_bar_charts({tested, time}, file);
  fmt::print("wrote {}\n", file.string());
#else
  (void)datasets, (void)methods, (void)rows;
  fmt::print("note: built without rendering: no chart {}\n", file.string());
#endif
}

}  // namespace

void run_bench_search(const SearchBenchOptions& opt) {
  const std::vector<std::string> methods =
      opt.methods.empty() ? search_method_names() : opt.methods;
  for (const std::string& m : methods) (void)make_search(m);  // unknown names: exit 2 up front
  const std::filesystem::path out = opt.out;
  make_output_dir(out);
  const RollingState rolling = rolling_state(opt.scene, opt.plan);
  fmt::print("flowing state     {} ({} particles): {}\n", rolling.scene.name,
             rolling.state.particles.size(), rolling.origin);

  std::vector<Dataset> datasets;
  {
    Dataset flowing{rolling.scene.name + "_flowing",
                    rolling.state.particles.position,
                    rolling.state.particles.radius,
                    std::nullopt,
                    std::nullopt,
                    nullptr,
                    true};
    if (rolling.scene.drum.ends == DrumEnds::periodic) flowing.period_z = rolling.scene.drum.depth;
    datasets.push_back(std::move(flowing));
  }
  if (opt.table1) datasets.push_back(paper_dataset(1));
  if (opt.table2) datasets.push_back(paper_dataset(2));

  fmt::print(
      "times per particle and call (ns), median of the repeats; build = laying the grid and "
      "sorting particles into cells (Verlet: the first call's list build), visit = candidate "
      "distance tests (Verlet: re-testing the list), both timed inside the engine\n");
  fmt::print("{:<20} {:<14} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9} {:>7} {:>9}\n",
             "dataset", "method", "cells/p", "tested/p", "tst/cont", "call ns", "build ns",
             "visit ns", "step ns", "ops/p", "search%", "paper ops");
  std::vector<SearchRow> rows;
  std::vector<std::string> names;
  for (const Dataset& d : datasets) {
    names.push_back(d.name);
    for (const std::string& m : methods) {
      if (m == "brute" && !d.brute) continue;
      SearchRow row = measure_search(d, m, opt.repeats);
      if (&d == &datasets.front()) measure_steps(rolling, row, opt.steps);
      print_row(row);
      std::fflush(stdout);  // rows as they come, also into a pipe or file
      rows.push_back(std::move(row));
    }
  }
  fmt::print(
      "ops/p = cells visited + pairs tested per particle (drumlab's count of the paper's "
      "operations); paper ops: the paper's estimate (Tables 1/2), brute only on the flowing "
      "state\n");
  const auto csv = out / fmt::format("search_{}.csv", rolling.scene.name);
  write_csv(csv, rows);
  fmt::print("wrote {}\n", csv.string());
  write_chart(out / fmt::format("search_{}.png", rolling.scene.name), names, methods, rows);
}

}  // namespace drumlab::bench
