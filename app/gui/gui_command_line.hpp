#pragma once
// The command line of drumlab-gui (app/gui/main.cpp), apart from its main so that the fuzz harness
// tests/fuzz/fuzz_cli_gui.cpp parses the very same options: declare_options, CLI11's parse, then
// finish_options.
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/gui/gui_options.hpp"

namespace drumlab::gui {

/// The command line as parsed: the options, and the flags that need a second look.
struct CommandLine {
  GuiOptions o;
  std::string switch_at, focus;
  std::vector<double> orbit, pick;
  std::uint64_t bench_frames = 100;
};

/// Declares every option of drumlab-gui on `app`, each parsed into `c`.
void declare_options(CLI::App& app, CommandLine& c);

/// The flags CLI11 has checked the form of, turned into options; and what they need together.
/// Throws InputError (an unknown --switch-at method, a headless flag without --frames).
void finish_options(CommandLine& c);

}  // namespace drumlab::gui
