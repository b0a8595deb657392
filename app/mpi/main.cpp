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
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/mpi/mpi_run.hpp"
#include "engine/openmp_waiting.hpp"
#include "engine/types.hpp"

namespace {

using drumlab::mpi::MpiRunOptions;

/// `drumlab run`'s arguments (app/run/run_options.hpp) and the decomposition's.
void add_run(CLI::App& app, MpiRunOptions& o, std::string& balance) {
  auto* run = app.add_subcommand("run", "fill (or restart), settle and turn a scene on all ranks");
  drumlab::cli::add_run_arguments(run, o.run);
  run->add_flag("--gather-output", o.gather_output,
                "gather checkpoints and series on rank 0 and write them there (no MPI-IO)");
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
  std::string balance = "time";
  add_run(app, o, balance);
  int code = 0;
  try {
    app.parse(argc, argv);
    o.balance = balance == "count" ? drumlab::BalanceBy::count : drumlab::BalanceBy::time;
    drumlab::mpi::run_mpi(MPI_COMM_WORLD, o);
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
