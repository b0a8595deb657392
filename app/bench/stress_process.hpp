#pragma once
// Runs this very `drumlab` executable (/proc/self/exe) as a child process, for stress cases that
// must see exit codes and messages as a user does.
#include <filesystem>
#include <string>

namespace drumlab::bench {

struct ChildResult {
  int exit_code = -1;  ///< -1: killed by a signal (a crash)
  std::string out;     ///< stdout
  std::string err;     ///< stderr
};

/// Runs `drumlab ARGS` in `work` (stdout and stderr captured through files there). `args` is
/// passed to the shell as is: quote paths with shell_quote.
ChildResult run_drumlab(const std::string& args, const std::filesystem::path& work);
/// 'text' with single quotes escaped for /bin/sh.
std::string shell_quote(const std::string& text);
/// Lines of `text` that are not empty.
std::size_t line_count(const std::string& text);

}  // namespace drumlab::bench
