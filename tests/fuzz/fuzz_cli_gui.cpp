// libFuzzer harness: the command line of `drumlab-gui` (app/gui/gui_command_line.hpp): declared,
// parsed and finished (finish_options), never run (no window). The input is the arguments after
// the program's name, split at NUL and newline (one a line in tests/data/fuzz/cli_gui/). It must
// end in a CLI::ParseError (CLI::Success for --help) or an InputError (CLI11's checks or
// finish_options'), or give options; anything else escapes (libFuzzer reports an uncaught
// exception as a crash).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/gui/gui_command_line.hpp"
#include "engine/types.hpp"
#include "tests/fuzz/cli_fuzz_args.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  drumlab::fuzz::FuzzArgs args("drumlab-gui", data, size);
  drumlab::gui::CommandLine c;  // as app/gui/main.cpp
  c.o.scene = "scenes/drum_demo.toml";
  CLI::App app{"drumlab-gui"};
  drumlab::gui::declare_options(app, c);
  std::vector<std::function<void()>> kept;  // never run; alive while parsing
  drumlab::fuzz::take_callbacks(app, kept);
  try {
    app.parse(args.argc(), args.argv());
    drumlab::gui::finish_options(c);
  } catch (const CLI::ParseError&) {
  } catch (const drumlab::InputError&) {
  }
  return 0;
}
