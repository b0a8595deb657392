#pragma once
// The command line of drumlab-mpi (app/mpi/main.cpp), apart from its main so that the fuzz
// harness tests/fuzz/fuzz_cli_mpi.cpp parses the very same options. It includes mpi.h (through
// app/mpi/mpi_run.hpp) but calls no MPI function.
#include <string>

#include <CLI/CLI.hpp>

#include "app/mpi/mpi_run.hpp"

namespace drumlab::mpi {

/// The `run` subcommand: `drumlab run`'s arguments (app/run/run_options.hpp) and the
/// decomposition's, into `o`; --balance as given ("time" or "count", checked by CLI11) into
/// `balance`, which the caller turns into o.balance after parsing.
void add_run(CLI::App& app, MpiRunOptions& o, std::string& balance);

}  // namespace drumlab::mpi
