#include "app/bench/stress_process.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace drumlab::bench {

namespace {

std::string read_all(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::string shell_quote(const std::string& text) {
  std::string q = "'";
  for (const char c : text) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  return q + "'";
}

std::size_t line_count(const std::string& text) {
  std::size_t n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) ++n;
  }
  return n;
}

ChildResult run_drumlab(const std::string& args, const std::filesystem::path& work) {
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe");
  const std::filesystem::path out = work / "child.stdout";
  const std::filesystem::path err = work / "child.stderr";
  const std::string command = fmt::format(
      "cd {} && {} {} >{} 2>{} </dev/null", shell_quote(work.string()), shell_quote(exe.string()),
      args, shell_quote(out.string()), shell_quote(err.string()));
  const int status = std::system(command.c_str());
  ChildResult r;
  // The shell reports a child killed by signal S as exit status 128 + S.
  if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) < 128)
    r.exit_code = WEXITSTATUS(status);
  r.out = read_all(out);
  r.err = read_all(err);
  return r;
}

}  // namespace drumlab::bench
