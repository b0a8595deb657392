// drumlab bench throughput [--scene S] [--threads N] [--methods LIST] [--steps N] [--out DIR]
// drumlab bench search [--scene S] [--methods LIST] [--table2] [--out DIR]
// drumlab bench accuracy [--scene S] [--quick] [--out DIR]
// drumlab bench skips [--scene S] [--steps N] [--repeats R] [--out DIR]
// drumlab bench regimes [--scene S] [--froude LIST] [--quick] [--out DIR]
// drumlab bench roofline [--scene S] [--method M] [--threads N] [--steps N] [--out DIR]
// Benchmarks that print figures (speed targets live here, not in timed tests): see
// bench_throughput.hpp and bench_search.hpp.
#include <memory>

#include "app/bench/bench_accuracy.hpp"
#include "app/bench/bench_regimes.hpp"
#include "app/bench/bench_roofline.hpp"
#include "app/bench/bench_search.hpp"
#include "app/bench/bench_skips.hpp"
#include "app/bench/bench_throughput.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/scene_setup.hpp"
#include "app/run/count_option.hpp"

namespace drumlab::cli {

namespace {

/// Options both benchmarks share: the scene and how its rolling state is prepared.
void add_state_options(CLI::App* cmd, std::string& scene, bench::RollingPlan& plan,
                       std::string& out) {
  cmd->add_option("--scene", scene, "scene file (default: scenes/drum_demo.toml)");
  cmd->add_option("--settle-time", plan.settle_time,
                  "s of settling before the drum turns (default: the scene's fill.settle_time)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--turn", plan.turn_revolutions, "drum revolutions after settling")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--fresh", plan.fresh, "prepare the rolling state again, ignoring the cache");
  cmd->add_option("--cache", plan.cache_dir, "folder of the cached rolling states")
      ->capture_default_str();
  cmd->add_option("--out", out, "folder for the CSV and PNG")->capture_default_str();
}

/// `bench skips`: the speed each skip of scene_features() gains (bench_skips.hpp).
void add_skips_subcommand(CLI::App* bench) {
  auto k = std::make_shared<bench::SkipsBenchOptions>();
  CLI::App* cmd = bench->add_subcommand(
      "skips", "Speed gained by each skip (friction, rolling, 2D grid, periodic ends, writers)");
  add_state_options(cmd, k->scene, k->plan, k->out);
  cmd->add_option("--steps", k->steps, "timed steps per run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--repeats", k->repeats, "runs per variant (median kept)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--every", k->every, "writer cadence in steps (default: steps / 10)")
      ->check(whole_count());
  cmd->add_option("--tiny", k->tiny, "coefficient that forces the general path")
      ->capture_default_str();
  cmd->callback([k] {
    if (k->scene.empty()) k->scene = shipped_scene("drum_demo.toml");
    bench::run_bench_skips(*k);
  });
}

/// `bench regimes`: the drum regime map (bench_regimes.hpp).
void add_regimes_subcommand(CLI::App* bench) {
  auto r = std::make_shared<bench::RegimesBenchOptions>();
  CLI::App* cmd = bench->add_subcommand(
      "regimes", "Regime map: observed flow regime and angle of repose against Fr = 3e-5..3");
  cmd->add_option("--scene", r->scene, "scene file (default: scenes/regime_drum.toml)");
  cmd->add_option("--froude", r->froude, "Froude numbers (default: 3e-5 ... 3)")->delimiter(',');
  cmd->add_option("--column-width", r->column_width,
                  "surface column width, m (default: two largest diameters)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quick", r->quick, "4 Froude numbers, short transient and window (< 1 min)");
  cmd->add_option("--settle-time", r->plan.settle_time,
                  "s of settling at rest (default: the scene's fill.settle_time)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--fresh", r->plan.fresh, "settle again, ignoring the cache");
  cmd->add_option("--cache", r->plan.cache_dir, "folder of the cached settled states")
      ->capture_default_str();
  cmd->add_option("--out", r->out, "folder for the CSV and PNG")->capture_default_str();
  cmd->callback([r] {
    if (r->scene.empty()) r->scene = shipped_scene("regime_drum.toml");
    bench::run_bench_regimes(*r);
  });
}

/// `bench roofline`: per phase, the work, the rates and the bound (bench_roofline.hpp).
void add_roofline_subcommand(CLI::App* bench) {
  auto r = std::make_shared<bench::RooflineOptions>();
  CLI::App* cmd = bench->add_subcommand(
      "roofline", "Per phase of the step: flops and bytes, their share of the machine's limits");
  add_state_options(cmd, r->scene, r->plan, r->out);
  cmd->add_option("--method", r->method, "search method (default: the scene's)");
  cmd->add_option("--threads", r->threads, "OpenMP threads")->check(CLI::Range(1, 1024));
  cmd->add_option("--steps", r->steps, "timed steps")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--warmup", r->warmup, "untimed steps before timing")
      ->check(whole_count())
      ->capture_default_str();
  cmd->add_flag("--quick", r->quick, "short machine measurements (coarse roofs)");
  cmd->callback([r] {
    if (r->scene.empty()) r->scene = shipped_scene("drum_demo.toml");
    bench::run_bench_roofline(*r);
  });
}

}  // namespace

void add_bench_command(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks: throughput, contact search, accuracy, skips, regimes, roofline");
  bench->require_subcommand(1);

  auto t = std::make_shared<bench::ThroughputOptions>();
  CLI::App* throughput = bench->add_subcommand(
      "throughput", "Particle-steps/s of a scene's rolling state for each search method");
  add_state_options(throughput, t->scene, t->plan, t->out);
  throughput->add_option("--threads", t->threads, "also run with N OpenMP threads")
      ->check(CLI::Range(1, 1024));
  throughput->add_option("--methods", t->methods, "search methods (default: all but brute)")
      ->delimiter(',');
  throughput->add_option("--steps", t->steps, "timed steps per method")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  throughput->add_option("--warmup", t->warmup, "untimed steps before timing")
      ->check(whole_count())
      ->capture_default_str();
  throughput
      ->add_option("--sort-every", t->sort_every,
                   "particle re-ordering intervals to compare, e.g. 0,25,100,1000 (0: never; "
                   "default: the scene's performance.sort_every)")
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  throughput->add_flag("--dry-too", t->dry_too,
                       "also run each method dry: the scene without [liquid] and [cohesion], on "
                       "the same particles");
  throughput->add_option("--repeats", t->repeats, "runs per row, the fastest kept")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  throughput->callback([t] {
    if (t->scene.empty()) t->scene = shipped_scene("drum_demo.toml");
    bench::run_bench_throughput(*t);
  });

  auto s = std::make_shared<bench::SearchBenchOptions>();
  CLI::App* search = bench->add_subcommand(
      "search", "Every search method on the flowing demo drum and the paper's packings");
  add_state_options(search, s->scene, s->plan, s->out);
  search->add_option("--methods", s->methods, "search methods (default: all)")->delimiter(',');
  search->add_flag("!--no-table1", s->table1, "leave out the paper's Table 1 packing (192k)");
  search->add_flag("--table2", s->table2, "add the paper's Table 2 packing (2.6M particles)");
  search->add_option("--repeats", s->repeats, "timed calls per method (median kept)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  search->add_option("--steps", s->steps, "dynamic steps per method on the flowing state")
      ->check(whole_count())
      ->capture_default_str();
  search->callback([s] {
    if (s->scene.empty()) s->scene = shipped_scene("drum_demo.toml");
    bench::run_bench_search(*s);
  });

  auto a = std::make_shared<bench::AccuracyOptions>();
  CLI::App* accuracy = bench->add_subcommand(
      "accuracy", "Run time against error: time step and search sweeps (see bench_accuracy.hpp)");
  add_state_options(accuracy, a->scene, a->plan, a->out);
  accuracy->get_option("--scene")->description(
      "scene file (default: scenes/accuracy_drum.toml; --quick: scenes/accuracy_quick.toml)");
  accuracy->add_flag("--quick", a->quick,
                     "short windows; --turn 0.2 and scenes/accuracy_quick.toml unless given");
  accuracy->callback([a, accuracy] {
    if (a->quick && accuracy->count("--turn") == 0) {
      a->plan.turn_revolutions = bench::kAccuracyQuickTurnRevolutions;
    }
    bench::run_bench_accuracy(*a);
  });
  add_skips_subcommand(bench);
  add_regimes_subcommand(bench);
  add_roofline_subcommand(bench);
}

}  // namespace drumlab::cli
