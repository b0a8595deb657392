#pragma once
// Runs the built `drumlab` executable in a shell and captures its exit code and output.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/small_drum_text.hpp"

namespace drumlab::test {

struct CliResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `command` in a shell with stdout and stderr captured together.
inline CliResult run_shell(const std::string& command) {
  CliResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

inline CliResult run_cli(const std::string& args) {
  return run_shell(std::string(DRUMLAB_CLI) + " " + args);
}

/// A small drum for CLI tests: 300 particles of two sizes, settling 0.01 s, a short run set by
/// `time_table` (the [time] keys); `header` is prepended (e.g. a name line).
inline std::string small_drum_scene(
    const std::string& time_table = "dt_factor = 0.2\nduration = 0.01",
    const std::string& header = "") {
  SmallDrumText t;
  t.header = header;
  t.time = time_table;
  t.output = "diagnostics_every = 20";
  return t.text();
}

/// A fresh directory under the system temp dir, removed at scope exit.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("drumlab-test-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path write(const std::string& file, const std::string& text) const {
    const auto p = path_ / file;
    std::ofstream(p) << text;
    return p;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace drumlab::test
