// libFuzzer harness: the command line of `drumlab` (app/cli/commands.hpp), parsed and never run.
// The input is the arguments after the program's name, split at NUL and newline (one a line in
// tests/data/fuzz/cli_drumlab/). Every subcommand's callback is taken out (kept, never run), so
// only the parsing runs: CLI11's and the options' own checks. It must end in a CLI::ParseError (bad
// arguments; CLI::Success for --help) or an InputError, or parse; anything else escapes
// (libFuzzer reports an uncaught exception as a crash).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/cli/commands.hpp"
#include "engine/types.hpp"
#include "tests/fuzz/cli_fuzz_args.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  drumlab::fuzz::FuzzArgs args("drumlab", data, size);
  CLI::App app{"drumlab"};
  drumlab::cli::add_commands(app);          // as app/cli/main.cpp
  std::vector<std::function<void()>> kept;  // never run; alive while parsing
  drumlab::fuzz::take_callbacks(app, kept);
  try {
    app.parse(args.argc(), args.argv());
  } catch (const CLI::ParseError&) {  // CLI::Success (--help) included
  } catch (const drumlab::InputError&) {
  }
  return 0;
}
