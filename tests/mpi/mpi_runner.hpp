#pragma once
// Runs `drumlab run` and `mpirun -np N drumlab-mpi run` on a small scene and reads back their
// checkpoints, for the mpi tests.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "engine/io/checkpoint.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {

using Ran = CliResult;

/// A command line (mpirun ...) with its output: the one shell runner of the tests.
inline Ran shell(const std::string& command) {
  return run_shell(command);
}

/// A file's whole text ("" if it cannot be read).
inline std::string read_text(const std::string& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The mpirun command for `ranks` ranks (root allowed, more ranks than cores allowed), or the
/// empty string when no launcher was found at configure time.
/// Each test process gives its mpiruns a session folder base of its own: two mpiruns of two tests
/// (ctest -j) starting at once both create /tmp/ompi.HOST.UID and one fails ("A call to mkdir was
/// unable to create the desired directory ... File exists", seen under load).
inline std::string mpirun(int ranks) {
  const std::string launcher = DRUMLAB_MPIEXEC;
  if (launcher.empty()) return {};
  struct SessionBase {  // removed with the test process, as TempDir is with its test
    std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("drumlab-ompi-" + std::to_string(::getpid()));
    SessionBase() { std::filesystem::create_directories(dir); }
    ~SessionBase() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  };
  static const SessionBase session_base;
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
         "OMPI_MCA_mpi_yield_when_idle=1 OMPI_MCA_orte_tmpdir_base=" +
         session_base.dir.string() + " " + launcher + " --oversubscribe -np " +
         std::to_string(ranks) + " ";
}

/// A test that runs `drumlab run` and `drumlab-mpi run` in its own temporary directory and reads
/// back their final checkpoints.
class MpiCase : public ::testing::Test {
 protected:
  TempDir tmp{std::string("mpi-") +
              ::testing::UnitTest::GetInstance()->current_test_info()->name()};
  struct Files {
    const TempDir& d;
    std::string file(const std::string& name) const { return (d.path() / name).string(); }
    std::string write(const std::string& name, const std::string& text) const {
      return d.write(name, text).string();
    }
  } dir{tmp};
  std::string last_output;  ///< of the latest parallel()

  void SetUp() override {
    if (mpirun(1).empty()) FAIL() << "mpirun not found at configure time (Debian: openmpi-bin)";
  }
  SimulationState serial(const std::string& scene, const std::string& args,
                         const std::string& out) {
    const Ran r = shell(std::string(DRUMLAB_CLI) + " run " + scene + " --threads 1 " + args +
                        " --checkpoint " + dir.file(out));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return read_checkpoint(dir.file(out)).state;
  }
  SimulationState parallel(int ranks, const std::string& scene, const std::string& args,
                           const std::string& out, int threads = 1) {
    const std::string t = std::to_string(threads);
    const Ran r =
        shell(mpirun(ranks) + "-x OMP_NUM_THREADS=" + t + " " + DRUMLAB_MPI_CLI + " run " + scene +
              " --threads " + t + " " + args + " --checkpoint " + dir.file(out));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    if (ranks > 1) {  // particles did migrate
      EXPECT_EQ(r.output.find(" 0 exchanges"), std::string::npos) << r.output;
      EXPECT_EQ(r.output.find(", 0 kept (motion only)"), std::string::npos) << r.output;
    }
    EXPECT_NE(r.output.find("ranks             " + std::to_string(ranks) + " x " + t),
              std::string::npos)
        << r.output;
    last_output = r.output;
    return read_checkpoint(dir.file(out)).state;
  }
};

}  // namespace drumlab::test
