// drumlab-gui: the interactive workbench (GLFW + Dear ImGui + the VTK drum view). Headless driving
// for tests and benchmarks: --frames N --screenshot FILE.png, --bench. Exit codes: 0 success,
// 2 bad input (one line), 1 anything else (no display, a failed run).
#include <charconv>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/gui/gui_app.hpp"
#include "app/gui/gui_options.hpp"
#include "engine/openmp_waiting.hpp"

namespace {

/// The command line as parsed: the options, and the flags that need a second look.
struct CommandLine {
  drumlab::gui::GuiOptions o;
  std::string switch_at, focus;
  std::vector<double> orbit, pick;
  std::uint64_t bench_frames = 100;
};

void declare_options(CLI::App& app, CommandLine& c) {
  app.add_option("scene", c.o.scene, "scene file (default: scenes/drum_demo.toml)");
  app.add_option("--method", c.o.method,
                 "search method (auto, brute, m1..m5, mlgrid, verlet[:GRID])");
  app.add_option("--focus", c.focus, "stable id of the particle whose search is shown, or auto")
      ->check(CLI::IsMember({"auto"}) |
              CLI::Range(drumlab::Index{0}, std::numeric_limits<drumlab::Index>::max()));
  app.add_option("--switch-at", c.switch_at, "K:METHOD: switch the search after K turning steps");
  app.add_option("--color-by", c.o.color_by, "size, speed, omega, id, coordination, ...");
  app.add_option("--camera", c.o.camera, "axis or iso");
  app.add_option("--settle-time", c.o.settle_time,
                 "s with the drum at rest first (default: scene)");
  app.add_option("--steps-per-frame", c.o.steps_per_frame, "simulation steps per snapshot")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000}));
  app.add_option("--threads", c.o.threads, "simulation threads")->check(CLI::Range(1, 256));
  app.add_option("--team", c.o.team,
                 "with --threads N > 1: adaptive (time N and 1 thread now and then, run the "
                 "faster; the same results) or fixed (always N)")
      ->check(CLI::IsMember({"adaptive", "fixed"}));
  app.add_option("--size", c.o.width, "window width (height: --height)")
      ->check(CLI::Range(320, 8192));
  app.add_option("--height", c.o.height, "window height")->check(CLI::Range(240, 8192));
  app.add_option("--frames", c.o.frames,
                 "headless: run N frames (steps-per-frame steps each), exit");
  app.add_option("--screenshot", c.o.screenshot,
                 "headless: save the whole window as PNG at the end");
  app.add_option("--checkpoint", c.o.checkpoint,
                 "headless: save the final state (HDF5) at the end");
  app.add_flag("--zoom-to-focus", c.o.zoom_to_focus, "frame the focus particle's search");
  app.add_flag("--teach", c.o.teach, "open the teaching panel");
  app.add_option("--teach-method", c.o.teach_method, "the teaching panel's method (m1..m5)");
  app.add_option("--teach-cells", c.o.teach_cells, "cells of the walk shown (default: all)");
  app.add_option("--edit", c.o.edits, "KEY=VALUE: edit the scene panel's field (repeatable)");
  app.add_option("--save-scene", c.o.save_scene, "headless: save the edited scene as TOML");
  app.add_option("--orbit", c.orbit,
                 "headless: AZ,EL degrees: turn the camera before the last frame")
      ->delimiter(',')
      ->expected(2);
  app.add_option("--zoom", c.o.zoom,
                 "headless: zoom the camera by this factor before the last frame")
      ->check(CLI::Range(0.01, 100.0));
  app.add_option("--pick", c.pick,
                 "headless: X,Y: click the window pixel (column, row from the top) to focus the "
                 "front-most particle there, before the last frame")
      ->delimiter(',')
      ->expected(2);
  app.add_flag("!--no-inset", c.o.inset, "no focus inset");
  app.add_flag("--bench", c.o.bench, "print frames/s paused and running, and particle-steps/s");
  app.add_option("--bench-frames", c.bench_frames, "frames per --bench measurement");
}

/// The flags CLI11 has checked the form of, turned into options; and what they need together.
void finish_options(CommandLine& c) {
  drumlab::gui::GuiOptions& o = c.o;
  if (!c.switch_at.empty()) o.switch_at = drumlab::gui::parse_switch_at(c.switch_at);
  if (!c.orbit.empty()) o.orbit = std::array<double, 2>{c.orbit[0], c.orbit[1]};
  if (!c.pick.empty()) o.pick = std::array<double, 2>{c.pick[0], c.pick[1]};
  if (!c.focus.empty() && c.focus != "auto") {  // an id in range: CLI11 checked it
    drumlab::Index id = 0;
    std::from_chars(c.focus.data(), c.focus.data() + c.focus.size(), id);
    o.focus_id = id;
  }
  o.focus = c.focus;
  if ((!o.screenshot.empty() || !o.checkpoint.empty() || !o.save_scene.empty() || o.orbit ||
       o.pick || o.zoom != 1.0) &&
      o.frames == 0) {
    throw drumlab::InputError(
        "--screenshot, --checkpoint, --save-scene, --orbit, --zoom and --pick need --frames N");
  }
}

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
  declare_options(app, c);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "drumlab-gui: error: {}\n", e.what());
    return 2;
  }
  try {
    finish_options(c);
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
