// drumlab-mpi: the drum on N MPI ranks (issue 15). Run it with mpirun:
//   mpirun -np 4 drumlab-mpi run scenes/drum_demo.toml --steps 2000 --checkpoint out/state.h5
// Exit codes as drumlab's: 0 success, 1 unexpected failure, 2 bad input, 3 unstable. An error is
// printed once (by rank 0, or by the rank that met it if only one did) and every rank exits.
#include <mpi.h>

#include <malloc.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/mpi/mpi_run.hpp"
#include "engine/openmp_waiting.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/types.hpp"

namespace {

using drumlab::mpi::MpiRunOptions;

void add_run(CLI::App& app, MpiRunOptions& o, std::optional<std::uint64_t>& steps,
             std::string& balance) {
  auto* run = app.add_subcommand("run", "fill (or restart), settle and turn a scene on all ranks");
  run->add_option("scene", o.session.scene_file, "scene TOML file")->required();
  run->add_option("--method", o.session.method,
                  fmt::format("contact search method: {}, or auto", drumlab::search_method_help()));
  auto* s = run->add_option("--steps", steps, "turning steps after settling");
  run->add_option("--revolutions", o.session.revolutions, "drum revolutions after settling")
      ->check(CLI::PositiveNumber)
      ->excludes(s);
  run->add_option("--settle-time", o.session.settle_time, "seconds of settling")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--dt-factor", o.session.dt_factor, "time step in Rayleigh times")
      ->check(CLI::PositiveNumber);
  run->add_option("--sort-every", o.session.sort_every, "re-order every K steps (0: never)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--skin", o.session.skin, "Verlet skin in smallest radii")
      ->check(CLI::Range(1e-6, 10.0));
  run->add_option("--threads", o.threads, "OpenMP threads per rank")->check(CLI::Range(1, 1024));
  run->add_option("--checkpoint", o.checkpoint,
                  "write a checkpoint (serial layout, parallel HDF5) at the end");
  run->add_option("--checkpoint-every", o.checkpoint_every, "also every K turning steps")
      ->check(CLI::PositiveNumber);
  run->add_option("--h5", o.h5,
                  "HDF5 series (+ XDMF) in the serial layout, parallel HDF5 (a scene with bonds "
                  "adds its bond graph and agglomerate labels)");
  run->add_option("--granule-age", o.granule_age,
                  "granule criterion of the series' agglomerate labels: bonds older than T s join "
                  "(0: plain components; default: one drum revolution)")
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--gather-output", o.gather_output,
                "gather checkpoints and series on rank 0 and write them there (no MPI-IO)");
  run->add_option("--every", o.every, "steps between series frames (default: 1/100 of the turn)");
  run->add_option("--restart", o.session.restart, "continue from a checkpoint (any rank count)");
  run->add_option("--rebalance-every", o.rebalance_every,
                  "steps between balance checks (0: keep the first cut; default 200)");
  run->add_option("--balance", balance,
                  "what a re-balance equalises: time (each rank's measured work, the default) or "
                  "count (owned particles)")
      ->check(CLI::IsMember({"time", "count"}));
  run->add_option("--balance-threshold", o.balance_threshold,
                  "by time: re-cut when the slowest rank's work exceeds the mean by more than "
                  "this share (default 0.05; 0: at every check)")
      ->check(CLI::Range(0.0, 10.0));
}

void print_summary(const drumlab::mpi::MpiRunSummary& s) {
  fmt::print("scene             {} ({} particles, search {})\n", s.scene, s.particles, s.method);
  if (!s.search_reason.empty())
    fmt::print("search auto       -> {}: {}\n", s.method, s.search_reason);
  fmt::print("ranks             {} x {} thread(s); waiting threads: {}\n", s.ranks, s.threads,
             drumlab::openmp_waiting_description());
  fmt::print("owned per rank    min {} / mean {:.1f} / max {} (max/mean {:.3f})\n", s.owned_min,
             s.owned_mean, s.owned_max, s.owned_mean > 0 ? s.owned_max / s.owned_mean : 0.0);
  fmt::print(
      "communication     {:.1f} % of the time inside MPI (mean over ranks; max {:.1f} %), "
      "{} exchanges ({:.2f} s, slowest rank), {} re-balances ({:.3f} s finding the cuts)\n",
      100.0 * s.comm_share_mean, 100.0 * s.comm_share_max, s.exchanges, s.exchange_seconds,
      s.rebalances, s.recut_seconds);
  if (s.ranks > 1 && s.rebalance_every > 0) {
    if (s.balance == drumlab::BalanceBy::count) {
      fmt::print("balance           by count, re-cut every {} steps\n", s.rebalance_every);
    } else if (s.first_imbalance > 0.0) {
      fmt::print(
          "balance           by time, checked every {} steps, re-cut above +{:.0f} %; slowest "
          "rank's work / mean: {:.3f} at the first check, {:.3f} at the last\n",
          s.rebalance_every, 100.0 * s.balance_threshold, s.first_imbalance, s.last_imbalance);
    } else {
      fmt::print("balance           by time, checked every {} steps (no check in this run)\n",
                 s.rebalance_every);
    }
  }
  const drumlab::StepTimers& t = s.split;
  if (t.total() > 0.0) {
    const double all = t.total();
    fmt::print(
        "time split        search {:.1f} %, forces {:.1f} %, walls {:.1f} %, integration with "
        "the ghost refresh and exchanges {:.1f} %, re-ordering {:.1f} % (mean over ranks)\n",
        100.0 * t.search / all, 100.0 * t.forces / all, 100.0 * t.walls / all,
        100.0 * t.integration / all, 100.0 * t.reorder / all);
  }
  fmt::print("ghosts            at the exchanges {} sent in full (new), {} kept (motion only)\n",
             s.ghosts_new, s.ghosts_kept);
  if (s.wet && s.ranks > 1) {
    fmt::print("bridge events     {} (liquid bridges formed or ruptured), replayed on every rank\n",
               s.bridge_events);
  }
  const double rate =
      s.turn_seconds > 0 ? static_cast<double>(s.particles * s.turn_steps) / s.turn_seconds : 0.0;
  fmt::print(
      "steps             {} settling + {} turning in {:.3f} s ({:.3g} particle-steps/s "
      "turning)\n",
      s.settle_steps, s.turn_steps, s.seconds, rate);
  if (s.checkpoints + s.frames > 0) {
    fmt::print("output            {} checkpoint(s) in {:.3f} s, {} series frame(s) in {:.3f} s\n",
               s.checkpoints, s.checkpoint_seconds, s.frames, s.frame_seconds);
  }
}

/// Prints the error: bad input (exit 2) is met by every rank alike and printed by rank 0; any
/// other failure may be one rank's alone, and that rank prints it.
int fail(int code, const char* kind, const std::string& what, int rank) {
  if (rank == 0 || code != 2) fmt::print(stderr, "drumlab-mpi: {}: {}\n", kind, what);
  return code;
}

/// Every exchange (every ~20 steps) needs each rank's arrays again, hundreds of MB on a large drum.
/// glibc serves blocks above its mmap threshold from fresh mappings and trims the heap's top back
/// to the kernel, so each exchange would fault them all in again (the Table 2 drum on 2 ranks:
/// 2.3 M page faults in 200 steps; app/bench/README.md, "MPI scaling"). Every block comes from
/// the heap instead and stays there when freed, for the next exchange to reuse: a rank's memory
/// stays at its peak until it exits.
void keep_freed_memory() {
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

}  // namespace

int main(int argc, char** argv) {
  drumlab::choose_openmp_waiting(argc, argv);  // before MPI_Init; may execute us again
  keep_freed_memory();
  std::signal(SIGXFSZ, SIG_IGN);
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  CLI::App app{"drumlab-mpi: the drumlab DEM on MPI ranks (run it with mpirun -np N)"};
  app.require_subcommand(1);
  MpiRunOptions o;
  std::optional<std::uint64_t> steps;
  std::string balance = "time";
  add_run(app, o, steps, balance);
  int code = 0;
  try {
    app.parse(argc, argv);
    o.session.steps = steps;
    o.balance = balance == "count" ? drumlab::BalanceBy::count : drumlab::BalanceBy::time;
    const auto summary = drumlab::mpi::run_mpi(MPI_COMM_WORLD, o);
    if (rank == 0) print_summary(summary);
  } catch (const CLI::ParseError& e) {
    if (rank == 0) app.exit(e);
    code = e.get_exit_code() != 0 ? 2 : 0;
  } catch (const drumlab::InputError& e) {
    code = fail(2, "error", e.what(), rank);
  } catch (const drumlab::UnstableError& e) {
    code = fail(3, "unstable", e.what(), rank);
  } catch (const std::exception& e) {
    code = fail(1, "failed", e.what(), rank);
  }
  if (code != 0 && code != 2) {
    // A failure met by one rank only would leave the others waiting in a collective: stop all.
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, code);
  }
  MPI_Finalize();
  return code;
}
