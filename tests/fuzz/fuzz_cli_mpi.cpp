// libFuzzer harness: the command line of `drumlab-mpi` (app/mpi/mpi_command_line.hpp), parsed and
// never run (no MPI call: no MPI_Init). The input is the arguments after the program's name, split
// at NUL and newline (one a line in tests/data/fuzz/cli_mpi/); callbacks taken out, never run. It
// must end in a CLI::ParseError (CLI::Success for --help) or an InputError, or parse; then
// --balance is "time" or "count" (CLI11 checked it).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/mpi/mpi_command_line.hpp"
#include "engine/types.hpp"
#include "tests/fuzz/cli_fuzz_args.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  drumlab::fuzz::FuzzArgs args("drumlab-mpi", data, size);
  CLI::App app{"drumlab-mpi"};  // as app/mpi/main.cpp
  app.require_subcommand(1);
  drumlab::mpi::MpiRunOptions o;
  std::string balance = "time";
  drumlab::mpi::add_run(app, o, balance);
  std::vector<std::function<void()>> kept;  // never run; alive while parsing
  drumlab::fuzz::take_callbacks(app, kept);
  try {
    app.parse(args.argc(), args.argv());
    if (balance != "time" && balance != "count") std::abort();
  } catch (const CLI::ParseError&) {
  } catch (const drumlab::InputError&) {
  }
  return 0;
}
