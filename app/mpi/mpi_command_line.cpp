#include "app/mpi/mpi_command_line.hpp"

namespace drumlab::mpi {

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

}  // namespace drumlab::mpi
