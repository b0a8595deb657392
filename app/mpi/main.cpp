// drumlab-mpi: the drum on N MPI ranks (issue 15). Run it with mpirun:
//   mpirun -np 4 drumlab-mpi run scenes/drum_demo.toml --steps 2000 --checkpoint out/state.h5
// Exit codes as drumlab's: 0 success, 1 unexpected failure, 2 bad input, 3 unstable. An error is
// printed once (by rank 0, or by the rank that met it if only one did) and every rank exits, never
// one left waiting (see fail()).
#include <mpi.h>

#include <malloc.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/mpi/mpi_command_line.hpp"
#include "app/mpi/mpi_run.hpp"
#include "engine/openmp_waiting.hpp"
#include "engine/types.hpp"

namespace {

using drumlab::mpi::MpiRunOptions;

/// Whether every rank has failed too: each failing rank calls this from its handler, on a
/// communicator of its own (so that it matches no collective of the run). An error the ranks
/// agreed on (bad input found by one rank and thrown on all, a write failed anywhere, an
/// instability in the reduced diagnostics) brings all of them here within moments; an error met
/// by this rank alone does not (the others wait in a collective of the run), and after
/// `seconds` this rank gives up on them.
bool every_rank_failed(MPI_Comm failures, double seconds) {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibarrier(failures, &request);
  const double t0 = MPI_Wtime();
  int done = 0;
  while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && done == 0 &&
         MPI_Wtime() - t0 < seconds) {
    usleep(1000);
  }
  return done != 0;
}

/// Ends a failed run with one line and `code` on every rank: printed by rank 0 when every rank
/// failed alike (then each leaves through MPI_Finalize), else by this rank, which then stops
/// every rank with MPI_Abort (mpirun exits with `code`), never leaving one waiting.
int fail(MPI_Comm failures, int code, const char* kind, const std::string& what, int rank) {
  const bool all = every_rank_failed(failures, 10.0);
  if (rank == 0 || !all) fmt::print(stderr, "drumlab-mpi: {}: {}\n", kind, what);
  if (!all) {
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, code);
  }
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
  drumlab::mpi::add_run(app, o, balance);
  MPI_Comm failures = MPI_COMM_NULL;
  MPI_Comm_dup(MPI_COMM_WORLD, &failures);
  int code = 0;
  try {
    app.parse(argc, argv);
    o.balance = balance == "count" ? drumlab::BalanceBy::count : drumlab::BalanceBy::time;
    drumlab::mpi::run_mpi(MPI_COMM_WORLD, o);
  } catch (const CLI::ParseError& e) {
    if (rank == 0) app.exit(e);
    code = e.get_exit_code() != 0 ? 2 : 0;
  } catch (const drumlab::InputError& e) {
    code = fail(failures, 2, "error", e.what(), rank);
  } catch (const drumlab::UnstableError& e) {
    code = fail(failures, 3, "unstable", e.what(), rank);
  } catch (const std::exception& e) {
    code = fail(failures, 1, "failed", e.what(), rank);
  }
  MPI_Comm_free(&failures);
  MPI_Finalize();
  return code;
}
