// A fuzz harness's scratch file: one per process under the system temp dir, removed when the
// process exits (libFuzzer's exit() and a replay's return run static destructors; a crash keeps
// it beside libFuzzer's own copy of the input).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace drumlab::fuzz {

class ScratchFile {
 public:
  explicit ScratchFile(const std::string& stem)
      : path_(std::filesystem::temp_directory_path() /
              (stem + "-" + std::to_string(::getpid()) + ".h5")) {}
  ~ScratchFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace drumlab::fuzz
