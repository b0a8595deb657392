#pragma once
// Runs `drumlab run` and `mpirun -np N drumlab-mpi run` on a small scene and reads back their
// checkpoints, for the mpi tests.

#include <string>

#include "engine/io/checkpoint.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {

using Ran = CliResult;

/// A command line (mpirun ...) with its output: the one shell runner of the tests.
inline Ran shell(const std::string& command) {
  return run_shell(command);
}

/// The mpirun command for `ranks` ranks (root allowed, more ranks than cores allowed), or the
/// empty string when no launcher was found at configure time.
inline std::string mpirun(int ranks) {
  const std::string launcher = DRUMLAB_MPIEXEC;
  if (launcher.empty()) return {};
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
         "OMPI_MCA_mpi_yield_when_idle=1 " +
         launcher + " --oversubscribe -np " + std::to_string(ranks) + " ";
}

}  // namespace drumlab::test
