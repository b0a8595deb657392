#pragma once
// Runs `drumlab run` and `mpirun -np N drumlab-mpi run` on a small scene and reads back their
// checkpoints, for the mpi tests.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <string>

#include "engine/io/checkpoint.hpp"

namespace drumlab::test {

struct Ran {
  int exit_code = -1;
  std::string output;
};

inline Ran shell(const std::string& command) {
  Ran r;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    r.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
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
