#pragma once
// What the command-line harnesses (fuzz_cli_*.cpp) share: the input's bytes as an argv, and a
// CLI::App whose subcommands run nothing when parsed.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace drumlab::fuzz {

/// The input as arguments: split at every NUL and newline (a seed file is one argument a line);
/// a trailing piece without a separator is an argument too. argv()[0] is `program`.
class FuzzArgs {
 public:
  FuzzArgs(const char* program, const std::uint8_t* data, std::size_t size) {
    args_.emplace_back(program);
    std::string arg;
    for (std::size_t k = 0; k < size; ++k) {
      const char c = static_cast<char>(data[k]);
      if (c == '\0' || c == '\n') {
        args_.push_back(arg);
        arg.clear();
      } else {
        arg.push_back(c);
      }
    }
    if (!arg.empty()) args_.push_back(arg);
    for (std::string& a : args_) argv_.push_back(a.data());
    argv_.push_back(nullptr);
  }
  int argc() const { return static_cast<int>(args_.size()); }
  char** argv() { return argv_.data(); }

 private:
  std::vector<std::string> args_;
  std::vector<char*> argv_;
};

/// CLI::App's callbacks, which it has no getter for (a pointer to a protected member, named
/// through a derived class).
struct AppCallbacks : CLI::App {
  static constexpr auto final_callback = &AppCallbacks::final_callback_;
  static constexpr auto parse_complete_callback = &AppCallbacks::parse_complete_callback_;
};

/// Takes the callbacks of `app` and of every subcommand under it (and option group) out into
/// `kept`, leaving none: CLI11 runs a subcommand's callback during parse, and that is the command
/// itself (a run, a benchmark). `kept` must outlive the parse: a callback may own what the
/// options parse into (app/cli's commands capture a shared_ptr to their options struct), so it
/// is kept, never run. Options' own callbacks and validators (add_option_function, ->check) stay:
/// they are the parsing under test.
inline void take_callbacks(CLI::App& app, std::vector<std::function<void()>>& kept) {
  kept.push_back(std::exchange(app.*AppCallbacks::final_callback, {}));
  kept.push_back(std::exchange(app.*AppCallbacks::parse_complete_callback, {}));
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    take_callbacks(*sub, kept);
  }
}

}  // namespace drumlab::fuzz
