// drumlab decompose SCENE --ranks R[,R2,...] [--weight count|pairs] [--no-settle]
//                  [--bandwidth-gbs G] [--latency-us L] [--rate P] [--rate-steps N] [--per-rank]
// The MPI domain decomposition on paper (engine/parallel/): fills (and settles) the scene with the
// RunSession every command uses, decomposes its particles by RCB into R boxes, and prints per rank
// (or min / mean / max over the ranks) owned and ghost particles, the imbalance, the bytes
// exchanged per step and the communication-to-computation ratio under a network model, against
// the one-core rate measured here on a short run.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "app/run/run_report.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/parallel/exchange_cost.hpp"
#include "engine/parallel/ghost_layer.hpp"
#include "engine/parallel/rcb.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/session/run_session.hpp"
#include "engine/threads.hpp"

namespace drumlab::cli {
namespace {

struct DecomposeOptions {
  std::string scene;
  std::vector<int> ranks;
  std::string weight = "count";
  std::string method;
  bool no_settle = false;
  double settle_time = -1.0;
  double bandwidth_gbs = 10.0;
  double latency_us = 2.0;
  double rate = 0.0;
  std::uint64_t rate_steps = 0;  ///< 0: as many as take a second
  bool per_rank = false;
  std::string restart;  ///< decompose a checkpoint's state instead of a fresh fill
};

struct Stat {
  double min = 0.0, mean = 0.0, max = 0.0;
};

template <class F>
Stat stat_of(const DecompositionCost& c, F&& f) {
  Stat s{1e300, 0.0, -1e300};
  for (const RankCost& r : c.ranks) {
    const double v = f(r);
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
    s.mean += v;
  }
  s.mean /= static_cast<double>(c.ranks.size());
  return s;
}

/// "x1 y1 z2": the cuts of the tree along each axis.
std::string cut_axes(const Decomposition& d) {
  int n[3] = {0, 0, 0};
  for (const RcbNode& node : d.nodes)
    if (!node.leaf()) ++n[node.axis];
  return fmt::format("x{} y{} z{}", n[0], n[1], n[2]);
}

void print_per_rank(const Decomposition& d, const DecompositionCost& c) {
  fmt::print(
      "  rank  owned     ghosts    nbrs  box [lo, hi] m                                  "
      "  KB/step   comm us  comp ms\n");
  for (int r = 0; r < d.ranks(); ++r) {
    const RankCost& rc = c.ranks[static_cast<std::size_t>(r)];
    const Box& b = d.boxes[static_cast<std::size_t>(r)];
    fmt::print(
        "  {:>4}  {:>8}  {:>8}  {:>4}  [{:.3f},{:.3f}]x[{:.3f},{:.3f}]x[{:.3f},{:.3f}]  "
        "{:>9.1f}  {:>8.1f}  {:>7.2f}\n",
        r, rc.owned, rc.ghosts, rc.neighbours, b.lo.x(), b.hi.x(), b.lo.y(), b.hi.y(), b.lo.z(),
        b.hi.z(), rc.bytes / 1e3, rc.comm * 1e6, rc.compute * 1e3);
  }
}

/// Per particle: 1 + the distances its own search computed in the last step (for a Verlet list,
/// its listed partners j > i): the particle's share of the pair work plus its own update.
std::vector<double> pair_weights(const Simulation& sim) {
  const auto tests = sim.search().pairs_tested_per_particle();
  std::vector<double> w(sim.particles().size(), 1.0);
  for (std::size_t i = 0; i < w.size() && i < tests.size(); ++i) w[i] += tests[i];
  return w;
}

/// Per rank: the sum of `w` over its particles.
std::vector<double> rank_sums(const Decomposition& d, const std::vector<double>& w) {
  std::vector<double> sums(static_cast<std::size_t>(d.ranks()), 0.0);
  for (std::size_t i = 0; i < w.size(); ++i) sums[static_cast<std::size_t>(d.owner[i])] += w[i];
  return sums;
}

double max_over_mean(const std::vector<double>& v) {
  double max = 0.0, sum = 0.0;
  for (const double x : v) {
    max = std::max(max, x);
    sum += x;
  }
  return sum > 0.0 ? max * static_cast<double>(v.size()) / sum : 0.0;
}

/// One core's particle-steps/s: --rate, or measured on the scene (--rate-steps, or chunks of 1,
/// 2, 4, ... steps until the run has taken a second). Returns the rate and where it came from.
std::pair<double, std::string> compute_rate(RunSession& session, const DecomposeOptions& opt) {
  if (opt.rate > 0.0) return {opt.rate, "--rate"};
  std::uint64_t steps = 0;
  double wall = 0.0;
  for (std::uint64_t chunk = opt.rate_steps > 0 ? opt.rate_steps : 1;
       steps == 0 || (opt.rate_steps == 0 && wall < 1.0 && steps < 100000); chunk *= 2) {
    const TurnResult turn = session.run_turn(chunk, 0, {});
    steps += turn.stats.steps;
    wall += turn.stats.wall_seconds;
  }
  const auto n = static_cast<double>(session.simulation().particles().size());
  return {n * static_cast<double>(steps) / std::max(wall, 1e-9),
          fmt::format("measured: {} steps of {} on one core, {:.2f} s", steps,
                      session.scene().search_method, wall)};
}

/// What every rank count shares: the run's state, the cost model's inputs.
struct DecomposeSetup {
  std::vector<double> work;     ///< 1 + pairs tested, per particle
  std::vector<double> weights;  ///< what RCB balances (empty: the count)
  Box domain;
  std::optional<double> period;
  GhostReach reach;
  NetworkModel net;
  double rate = 0.0;
};

/// The lines before the table: the reach, the domain, the weight, the rate and the network.
void print_setup(const DecomposeOptions& opt, const SceneConfig& run, const DecomposeSetup& s,
                 const std::string& rate_source) {
  const auto parsed = parse_search_method(run.search_method);
  const bool verlet = parsed && parsed->verlet;
  fmt::print(
      "reach             r + {:.6g} m (r: the ghost's radius; largest {:.6g} m) = r + r_max {:.6g} "
      "+ pair range {:.3g}{}\n",
      s.reach.beyond, s.reach.largest(), run.max_radius(), ContactModel(run).max_pair_range(),
      verlet ? fmt::format(" + Verlet skin {:.3g}", run.performance.verlet_skin * run.min_radius())
             : std::string(" (no Verlet skin: not a list)"));
  const Box& domain = s.domain;
  fmt::print(
      "domain            [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] m, {} ends\n",
      domain.lo.x(), domain.hi.x(), domain.lo.y(), domain.hi.y(), domain.lo.z(), domain.hi.z(),
      s.period ? "periodic" : "capped");
  fmt::print("weight            {}\n",
             opt.weight == "pairs"
                 ? "pairs: 1 + the pairs each particle's search tested in the last step"
                 : "count: one per particle");
  fmt::print("compute rate      {:.4g} particle-steps/s ({})\n", s.rate, rate_source);
  fmt::print(
      "network           {:g} GB/s and {:g} us per message; {} B per ghost per step (position, "
      "velocity, omega; pairs across a boundary computed on both sides, no forces back)\n",
      opt.bandwidth_gbs, opt.latency_us, kGhostBytesPerStep);
  fmt::print(
      "\n{:>6} {:>25} {:>6} {:>6} {:>25} {:>7} {:>5} {:>8} {:>8} {:>6} {:>8} {:>6} {:>7} {:>10} "
      "{:>6}\n",
      "ranks", "owned min/mean/max", "imbal", "work", "ghosts min/mean/max", "gh/own", "nbrs",
      "MB/step", "comm us", "twice", "comp ms", "c/c", "speedup", "cuts", "time s");
}

/// Decomposes into r ranks and prints its row (and the ranks' own rows when asked); returns the
/// seconds RCB and the ghost layer took.
double print_rank_count(const DecomposeOptions& opt, const Simulation& sim, const DecomposeSetup& s,
                        int r) {
  const auto positions = std::span<const Vec3>(sim.particles().position);
  const auto start = std::chrono::steady_clock::now();
  const Decomposition d = rcb_decompose(positions, s.weights, s.domain, r);
  const GhostLayer g = ghost_layer(d, positions, sim.particles().radius, s.reach, s.period);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<double> rank_work = rank_sums(d, s.work);
  const ContactList& listed = sim.contacts();
  const PairsAcross across = pairs_across(d, listed.row_start(), listed.col());
  const DecompositionCost c = decomposition_cost(d, g, s.rate, s.net, rank_work, &across);
  const Stat owned = stat_of(c, [](const RankCost& x) { return double(x.owned); });
  const Stat ghosts = stat_of(c, [](const RankCost& x) { return double(x.ghosts); });
  const Stat nbrs = stat_of(c, [](const RankCost& x) { return double(x.neighbours); });
  const Stat bytes = stat_of(c, [](const RankCost& x) { return x.bytes; });
  const double work_imbalance = max_over_mean(rank_work);
  fmt::print(
      "{:>6} {:>25} {:>6.3f} {:>6.3f} {:>25} {:>7.3f} {:>5.0f} {:>8.3f} {:>8.1f} {:>6.3f} "
      "{:>8.3f} {:>6.3f} {:>7.1f} {:>10} {:>6.2f}\n",
      r, fmt::format("{:.0f}/{:.0f}/{:.0f}", owned.min, owned.mean, owned.max),
      owned.mean > 0 ? owned.max / owned.mean : 0.0, work_imbalance,
      fmt::format("{:.0f}/{:.0f}/{:.0f}", ghosts.min, ghosts.mean, ghosts.max),
      owned.mean > 0 ? ghosts.mean / owned.mean : 0.0, nbrs.max, bytes.max / 1e6, c.step_comm * 1e6,
      c.duplicated, c.step_compute * 1e3, c.step_compute > 0 ? c.step_comm / c.step_compute : 0.0,
      c.speedup(), cut_axes(d), seconds);
  if (opt.per_rank || (opt.ranks.size() == 1 && r <= 16)) print_per_rank(d, c);
  return seconds;
}

void print_legend(std::size_t rank_counts, double seconds) {
  fmt::print(
      "\nimbal: max/mean owned; work: max/mean of the work 1 + pairs tested per particle "
      "(whatever --weight balances); gh/own: mean ghosts per owned particle; nbrs: most ranks one "
      "rank receives from; MB/step: most bytes one rank receives per step; comm: slowest rank's "
      "exchange (nbrs x latency + bytes / bandwidth); twice: the listed pairs across a boundary, "
      "computed by both ranks, over all pairs; comp: slowest rank's share of the work at the "
      "compute rate plus half its pairs across (its neighbour's share, computed again), each at "
      "a whole step's time over all pairs; c/c: comm / comp; speedup: one core's step time / (comp "
      "+ comm), "
      "exchange not overlapped; cuts: cut planes normal to each axis.\n");
  fmt::print("decomposition     {} rank counts in {:.2f} s (RCB + ghost layer)\n", rank_counts,
             seconds);
}

void decompose(const DecomposeOptions& opt) {
  if (!opt.method.empty() && opt.method != "auto") {
    try {
      make_search(opt.method);
    } catch (const InputError& e) {
      throw InputError(fmt::format("--method: {}", e.what()));
    }
  }
  const SceneConfig scene = load_dynamic_scene(opt.scene);
  set_thread_count(1);  // the rate is one core's
  SessionOptions so;
  so.scene_file = opt.scene;
  so.method = opt.method;
  so.settle_time = opt.no_settle ? 0.0 : opt.settle_time;
  so.steps = opt.rate > 0.0 ? 0 : opt.rate_steps;
  so.restart = opt.restart;
  const auto fill_start = std::chrono::steady_clock::now();
  RunSession session(scene, so);
  const Simulation& sim = session.simulation();
  const std::uint64_t start_step = sim.steps();
  const SceneConfig& run = session.scene();
  fmt::print("scene             {} ({}), {} particles, search {}\n", run.name, opt.scene,
             sim.particles().size(), run.search_method);
  const SessionPlan plan = session.plan();
  settle_with_progress(session, plan.settle_steps);
  DecomposeSetup setup;
  std::string rate_source;
  std::tie(setup.rate, rate_source) = compute_rate(session, opt);
  const double prepare_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - fill_start).count();
  const std::string state =
      !opt.restart.empty()    ? fmt::format("checkpoint {} (step {})", opt.restart, start_step)
      : plan.settle_steps > 0 ? fmt::format("fill + settle {} steps", plan.settle_steps)
                              : std::string("fill only (no settling)");
  fmt::print("state             {} ({:.1f} s incl. the rate run)\n", state, prepare_seconds);

  setup.work = pair_weights(sim);
  if (opt.weight == "pairs") setup.weights = setup.work;
  setup.domain = drum_domain(run.drum.diameter, run.drum.depth);
  if (run.drum.ends == DrumEnds::periodic) setup.period = run.drum.depth;
  setup.reach = ghost_reach(run);
  setup.net = NetworkModel{opt.bandwidth_gbs * 1e9, opt.latency_us * 1e-6};
  print_setup(opt, run, setup, rate_source);
  double total_seconds = 0.0;
  for (const int r : opt.ranks) total_seconds += print_rank_count(opt, sim, setup, r);
  print_legend(opt.ranks.size(), total_seconds);
}

}  // namespace

void add_decompose_command(CLI::App& app) {
  auto opt = std::make_shared<DecomposeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "decompose",
      "MPI domain decomposition on paper: RCB boxes, ghosts, bytes per step and the "
      "communication-to-computation ratio on the scene's real fill");
  cmd->add_option("scene", opt->scene, "scene file (TOML)")->required();
  cmd->add_option("--ranks", opt->ranks, "rank counts, comma-separated (e.g. 2,4,8)")
      ->required()
      ->delimiter(',')
      ->check(CLI::Range(1, 1'000'000));
  cmd->add_option("--weight", opt->weight,
                  "balance by particle count, or by work: 1 + pairs tested per particle")
      ->check(CLI::IsMember({"count", "pairs"}));
  cmd->add_option("--method", opt->method,
                  fmt::format("contact search method (overrides the scene): {}, or auto",
                              search_method_help()));
  cmd->add_flag("--no-settle", opt->no_settle, "decompose the fill as placed (no settling)");
  cmd->add_option("--settle-time", opt->settle_time, "seconds of settling (default: the scene's)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--bandwidth-gbs", opt->bandwidth_gbs, "network bandwidth per rank, GB/s")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--latency-us", opt->latency_us, "network latency per message, us")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--rate", opt->rate,
                  "one-core particle-steps/s (default: measured on a short run of the scene)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--rate-steps", opt->rate_steps,
                  "steps of the rate measurement (default: doubling from 1 until it took 1 s)")
      ->check(CLI::Range(1, 100000));
  cmd->add_flag("--per-rank", opt->per_rank, "one line per rank for every rank count");
  cmd->add_option("--restart", opt->restart,
                  "decompose the state of a checkpoint (e.g. a settled drum) instead of a fill");
  cmd->callback([opt] { decompose(*opt); });
}

}  // namespace drumlab::cli
