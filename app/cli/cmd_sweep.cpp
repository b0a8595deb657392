// drumlab sweep SCENE --set KEY=V1,V2,... [--set ...] [--seeds S1,S2,...] --out DIR [--jobs J]
// The scene once per combination of values (and per seed), each a `drumlab run` child process
// with --observables (and --agglomerates for a scene with bonds) in DIR/runs/NAME/; the drum
// observables' mean and spread over a window of each run go to DIR/sweep.csv (a row per finished
// run, rewritten after each), and DIR/sweep.png plots them against the first swept key. A killed
// sweep keeps its finished rows; run again, it runs only the rest.
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "app/cli/sweep_plan.hpp"
#include "app/cli/sweep_results.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/types.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/xy_chart.hpp"
#endif

namespace drumlab::cli {
namespace {

struct SweepOptions {
  std::string scene;
  std::vector<std::string> sets;
  std::vector<std::int64_t> seeds;
  std::string out;
  int jobs = 1;
  double window_from = -1.0;
  std::vector<std::string> run_args;  ///< passed to every `drumlab run`
};

/// Starts `drumlab run` for one run in `dir` (its output in dir/log.txt); the child dies with
/// the sweep (PR_SET_PDEATHSIG), so a killed sweep leaves no run behind.
pid_t start_run(const SweepRun& run, const std::filesystem::path& dir,
                const std::vector<std::string>& run_args) {
  std::vector<std::string> args{"/proc/self/exe", "run", (dir / "scene.toml").string()};
  args.insert(args.end(), run_args.begin(), run_args.end());
  args.insert(args.end(), {"--observables", (dir / "observables.csv").string()});
  if (run.has_bonds)
    args.insert(args.end(), {"--agglomerates", (dir / "agglomerates.csv").string()});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log = (dir / "log.txt").string();
  std::fflush(stdout);
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("sweep: fork failed");
  if (child == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(1);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::close(fd);
    }
    ::execv("/proc/self/exe", argv.data());
    ::_exit(127);
  }
  return child;
}

/// The last line of a run's log (its error, when it failed).
std::string last_line(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

void write_table(const std::filesystem::path& file, const std::string& header,
                 const std::vector<SweepRun>& runs,
                 const std::map<std::string, std::string>& rows) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << header << '\n';
    for (const SweepRun& r : runs) {
      if (const auto at = rows.find(r.name); at != rows.end()) out << at->second << '\n';
    }
  });
}

#ifdef DRUMLAB_WITH_RENDER
/// sweep.png: each run's window mean with its spread against the first swept key (its value, or
/// its position among the values when they are not numbers); the regime map (each run's regime,
/// and for a sweep over a planetary drum's speed ratio the closed form's critical ratios) with
/// the rules' evidence; and the agglomerates for a scene with bonds.
void write_chart(const std::filesystem::path& file, const SweepSet& first,
                 const std::vector<RunResult>& results, const std::vector<SweepRun>& runs,
                 bool bonds) {
  const auto x_of = [&](const RunResult& r) {
    char* end = nullptr;
    const double v = std::strtod(r.values.front().c_str(), &end);
    if (end != r.values.front().c_str() && *end == '\0') return v;
    return static_cast<double>(
        std::find(first.values.begin(), first.values.end(), r.values.front()) -
        first.values.begin());
  };
  const auto series = [&](std::size_t q, const char* name, double scale = 1.0) {
    render::XYSeries s;
    s.name = name;
    s.markers_only = true;
    for (const RunResult& r : results) {
      s.x.push_back(x_of(r));
      s.y.push_back(scale * r.mean[q]);
      s.y_error.push_back(scale * r.sd[q]);
    }
    return s;
  };
  std::vector<render::XYPanel> panels(1);
  panels[0].title = "angle of repose (window mean +- sd)";
  panels[0].x_label = first.key;
  panels[0].y_label = "degrees";
  panels[0].series = {series(0, "surface fit"), series(1, "centre of mass")};

  render::XYPanel map{"flow regime (rules: engine/analysis/flow_regime.hpp)",
                      first.key,
                      "0 resting 1 slumping 2 rolling 3 cascading 4 cataracting 5 centrifuging",
                      {}};
  double x_lo = 0.0, x_hi = 0.0;
  for (std::size_t k = 0; k < results.size(); ++k) {
    x_lo = k == 0 ? x_of(results[k]) : std::min(x_lo, x_of(results[k]));
    x_hi = k == 0 ? x_of(results[k]) : std::max(x_hi, x_of(results[k]));
  }
  for (std::size_t level = 0; level < std::size(kFlowRegimes); ++level) {
    render::XYSeries s{std::string(regime_name(kFlowRegimes[level])), {}, {}, false, true};
    for (const RunResult& r : results) {
      if (r.regime.regime != kFlowRegimes[level]) continue;
      s.x.push_back(x_of(r));
      s.y.push_back(static_cast<double>(level));
    }
    if (!s.x.empty()) map.series.push_back(s);
  }
  // A planetary drum swept over k: the wall holds a particle where |1 + k| exceeds its ratio.
  if (first.key == "drum.orbit.speed_ratio" && !runs.front().critical_ratios.empty()) {
    const std::vector<double>& ratios = runs.front().critical_ratios;
    const bool one_size = std::abs(ratios[1] - ratios[0]) <= 1e-9 * ratios[0];
    for (std::size_t c = 0; c < (one_size ? 1u : 2u); ++c) {
      for (const double sign : {1.0, -1.0}) {
        const double k = sign * ratios[c] - 1.0;
        if (k < x_lo || k > x_hi) continue;
        map.series.push_back({fmt::format("k = {:.3g}: the wall holds {} above |1 + k| = {:.3g}", k,
                                          one_size ? "a ball"
                                          : c == 0 ? "the largest"
                                                   : "the smallest",
                                          ratios[c]),
                              {k, k},
                              {-0.5, 5.5},
                              c == 0,
                              false});
      }
    }
  }
  render::XYPanel evidence{"regime evidence (window mean +- sd)", first.key, "share or ratio", {}};
  evidence.series = {series(7, "in flight x10", 10.0), series(10, "share above the axis"),
                     series(11, "centre of mass from the axis / R")};
  render::XYSeries slip{
      "speed against the wall / the wall's against the field", {}, {}, false, true};
  for (const RunResult& r : results) {
    slip.x.push_back(x_of(r));
    slip.y.push_back(r.regime.speed_ratio);
  }
  evidence.series.push_back(slip);
  panels.push_back(map);
  panels.push_back(evidence);
  if (bonds) {
    render::XYPanel agglomerates{"agglomerates (window mean +- sd)", first.key, "count", {}};
    agglomerates.series = {series(4, "agglomerates (size >= 2)"), series(5, "largest")};
    panels.push_back(agglomerates);
  }
  render::write_xy_charts(panels, file, 700 * static_cast<int>(panels.size()), 600);
}
#endif

void sweep(const SweepOptions& o) {
  std::vector<SweepSet> sets;
  for (const std::string& s : o.sets) sets.push_back(parse_sweep_set(s));
  const std::vector<SweepRun> runs = plan_sweep(o.scene, sets, o.seeds);
  const std::filesystem::path out = o.out;
  std::error_code ec;
  std::filesystem::create_directories(out / "runs", ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot create ({})", o.out, ec.message()));
  const std::string header = sweep_header(sets);
  const auto table = out / "sweep.csv";
  std::map<std::string, std::string> rows = read_sweep_rows(table, header);
  std::vector<const SweepRun*> todo;
  for (const SweepRun& r : runs) {
    if (!rows.count(r.name)) todo.push_back(&r);
  }
  fmt::print("sweep             {} runs ({} finished before), {} at a time, in {}\n", runs.size(),
             runs.size() - todo.size(), o.jobs, out.string());
  std::map<pid_t, std::pair<const SweepRun*, std::chrono::steady_clock::time_point>> running;
  std::size_t next = 0, failed = 0;
  while (next < todo.size() || !running.empty()) {
    while (next < todo.size() && running.size() < static_cast<std::size_t>(o.jobs)) {
      const SweepRun& r = *todo[next++];
      const auto dir = out / "runs" / r.name;
      std::filesystem::create_directories(dir);
      write_file_atomically(dir / "scene.toml", [&](std::ostream& s) { s << r.scene_text; });
      running[start_run(r, dir, o.run_args)] = {&r, std::chrono::steady_clock::now()};
    }
    int status = 0;
    const pid_t done = ::waitpid(-1, &status, 0);
    const auto at = running.find(done);
    if (at == running.end()) continue;
    const SweepRun& r = *at->second.first;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - at->second.second).count();
    running.erase(at);
    const auto dir = out / "runs" / r.name;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      ++failed;
      fmt::print("failed            {} ({:.1f} s): {}\n", r.name, seconds,
                 last_line(dir / "log.txt"));
      continue;
    }
    const RunResult result = summarise_run(r, dir, o.window_from);
    rows[r.name] = sweep_row(result);
    write_table(table, header, runs, rows);
    fmt::print(
        "done              {} ({:.1f} s): angle {:.1f} +- {:.1f} deg (centre of mass), "
        "{:.1f} +- {:.1f} (fit), {} frames from revolution {:.3g}; {}\n",
        r.name, seconds, result.mean[1], result.sd[1], result.mean[0], result.sd[0], result.frames,
        result.window_from, regime_name(result.regime.regime));
  }
  write_table(table, header, runs, rows);
  fmt::print("table             {} ({} rows)\n", table.string(), rows.size());
#ifdef DRUMLAB_WITH_RENDER
  std::vector<RunResult> results;
  bool bonds = false;
  for (const SweepRun& r : runs) {
    if (!rows.count(r.name)) continue;
    results.push_back(summarise_run(r, out / "runs" / r.name, o.window_from));
    bonds = bonds || r.has_bonds;
  }
  if (!results.empty()) {
    write_chart(out / "sweep.png", sets.front(), results, runs, bonds);
    fmt::print("chart             {}\n", (out / "sweep.png").string());
  }
#endif
  if (failed > 0) {
    throw InputError(
        fmt::format("{} of {} runs failed (their logs: {}/runs/*/log.txt); run the "
                    "sweep again to retry them",
                    failed, runs.size(), out.string()));
  }
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run a scene once per value of scene keys (and seeds); observables per run");
  cmd->add_option("scene", o->scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", o->sets,
                  "KEY=V1,V2,...: a dotted scene key and its values (repeat for a grid)")
      ->required();
  cmd->add_option("--seeds", o->seeds, "S1,S2,...: runs per value with fill.seed = each")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", o->out, "folder of the sweep (sweep.csv, sweep.png, runs/)")->required();
  cmd->add_option("--jobs", o->jobs, "runs at a time")->check(CLI::Range(1, 256));
  cmd->add_option("--window-from", o->window_from,
                  "revolutions after which frames count (default: the second half of each run)")
      ->check(CLI::NonNegativeNumber);
  auto pass = [o](const std::string& flag) {
    return [o, flag](const std::string& value) {
      o->run_args.push_back(flag);
      if (!value.empty()) o->run_args.push_back(value);
    };
  };
  for (const char* flag :
       {"--revolutions", "--steps", "--every", "--threads", "--method", "--settle-time",
        "--dt-factor", "--granule-age", "--granule-criterion", "--granule-resolution"}) {
    cmd->add_option_function<std::string>(flag, pass(flag), "as for drumlab run");
  }
  cmd->add_flag_callback(
      "--unsafe-dt", [o] { o->run_args.push_back("--unsafe-dt"); }, "as for drumlab run");
  cmd->callback([o] { sweep(*o); });
}

}  // namespace drumlab::cli
