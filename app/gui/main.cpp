// drumlab-gui: the interactive workbench (GLFW + Dear ImGui + the VTK drum view). Headless driving
// for tests and benchmarks: --frames N --screenshot FILE.png, --bench. Exit codes: 0 success,
// 2 bad input (one line), 1 anything else (no display, a failed run).
#include <cstdio>
#include <exception>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/gui/gui_app.hpp"
#include "app/gui/gui_command_line.hpp"
#include "app/gui/gui_options.hpp"
#include "engine/openmp_waiting.hpp"

namespace {

using drumlab::gui::CommandLine;

void run(const CommandLine& c) {
  drumlab::gui::GuiApp gui(c.o);
  if (!c.o.bench) {
    gui.run();
    return;
  }
  const auto b = gui.bench(c.bench_frames);
  const std::uint64_t steps = 300;
  const double cli = drumlab::gui::cli_particle_steps(c.o, steps);
  drumlab::gui::print_bench(c.o, b, c.bench_frames, cli, steps);
}

}  // namespace

int main(int argc, char** argv) {
  drumlab::choose_openmp_waiting(argc, argv);  // may execute the program again, see there
  CommandLine c;
  c.o.scene = DRUMLAB_SCENES_DIR "/drum_demo.toml";
  CLI::App app{"drumlab-gui: the drum workbench (run under xvfb-run for headless use)"};
  drumlab::gui::declare_options(app, c);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "drumlab-gui: error: {}\n", e.what());
    return 2;
  }
  try {
    drumlab::gui::finish_options(c);
    run(c);
  } catch (const drumlab::InputError& e) {
    fmt::print(stderr, "drumlab-gui: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "drumlab-gui: failed: {}\n", e.what());
    return 1;
  }
  return 0;
}
