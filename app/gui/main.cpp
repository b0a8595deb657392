// drumlab-gui: the interactive workbench (GLFW + Dear ImGui + the VTK drum view). Headless driving
// for tests and benchmarks: --frames N --screenshot FILE.png, --bench. Exit codes: 0 success,
// 2 bad input (one line), 1 anything else (no display, a failed run).
#include <charconv>
#include <cstdio>
#include <exception>
#include <limits>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/gui/gui_app.hpp"
#include "app/gui/gui_options.hpp"
#include "engine/openmp_waiting.hpp"

int main(int argc, char** argv) {
  drumlab::choose_openmp_waiting(argc, argv);  // may execute the program again, see there
  drumlab::gui::GuiOptions o;
  o.scene = DRUMLAB_SCENES_DIR "/drum_demo.toml";
  std::string switch_at, focus;
  std::uint64_t bench_frames = 100;
  CLI::App app{"drumlab-gui: the drum workbench (run under xvfb-run for headless use)"};
  app.add_option("scene", o.scene, "scene file (default: scenes/drum_demo.toml)");
  app.add_option("--method", o.method,
                 "search method (auto, brute, m1..m5, mlgrid, verlet[:GRID])");
  app.add_option("--focus", focus, "stable id of the particle whose search is shown, or auto")
      ->check(CLI::IsMember({"auto"}) |
              CLI::Range(drumlab::Index{0}, std::numeric_limits<drumlab::Index>::max()));
  app.add_option("--switch-at", switch_at, "K:METHOD: switch the search after K turning steps");
  app.add_option("--color-by", o.color_by, "size, speed, omega, id, coordination, ...");
  app.add_option("--camera", o.camera, "axis or iso");
  app.add_option("--settle-time", o.settle_time, "s with the drum at rest first (default: scene)");
  app.add_option("--steps-per-frame", o.steps_per_frame, "simulation steps per snapshot")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000}));
  app.add_option("--threads", o.threads, "simulation threads")->check(CLI::Range(1, 256));
  app.add_option("--team", o.team,
                 "with --threads N > 1: adaptive (time N and 1 thread now and then, run the "
                 "faster; the same results) or fixed (always N)")
      ->check(CLI::IsMember({"adaptive", "fixed"}));
  app.add_option("--size", o.width, "window width (height: --height)")
      ->check(CLI::Range(320, 8192));
  app.add_option("--height", o.height, "window height")->check(CLI::Range(240, 8192));
  app.add_option("--frames", o.frames, "headless: run N frames (steps-per-frame steps each), exit");
  app.add_option("--screenshot", o.screenshot, "headless: save the whole window as PNG at the end");
  app.add_option("--checkpoint", o.checkpoint, "headless: save the final state (HDF5) at the end");
  app.add_flag("--zoom-to-focus", o.zoom_to_focus, "frame the focus particle's search");
  app.add_flag("--teach", o.teach, "open the teaching panel");
  app.add_option("--teach-method", o.teach_method, "the teaching panel's method (m1..m5)");
  app.add_option("--teach-cells", o.teach_cells, "cells of the walk shown (default: all)");
  app.add_option("--edit", o.edits, "KEY=VALUE: edit the scene panel's field (repeatable)");
  app.add_option("--save-scene", o.save_scene, "headless: save the edited scene as TOML");
  std::vector<double> orbit, pick;
  app.add_option("--orbit", orbit, "headless: AZ,EL degrees: turn the camera before the last frame")
      ->delimiter(',')
      ->expected(2);
  app.add_option("--zoom", o.zoom, "headless: zoom the camera by this factor before the last frame")
      ->check(CLI::Range(0.01, 100.0));
  app.add_option("--pick", pick,
                 "headless: X,Y: click the window pixel (column, row from the top) to focus the "
                 "front-most particle there, before the last frame")
      ->delimiter(',')
      ->expected(2);
  app.add_flag("!--no-inset", o.inset, "no focus inset");
  app.add_flag("--bench", o.bench, "print frames/s paused and running, and particle-steps/s");
  app.add_option("--bench-frames", bench_frames, "frames per --bench measurement");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "drumlab-gui: error: {}\n", e.what());
    return 2;
  }
  try {
    if (!switch_at.empty()) o.switch_at = drumlab::gui::parse_switch_at(switch_at);
    if (!orbit.empty()) o.orbit = std::array<double, 2>{orbit[0], orbit[1]};
    if (!pick.empty()) o.pick = std::array<double, 2>{pick[0], pick[1]};
    if (!focus.empty() && focus != "auto") {  // an id in range: CLI11 checked it
      drumlab::Index id = 0;
      std::from_chars(focus.data(), focus.data() + focus.size(), id);
      o.focus_id = id;
    }
    o.focus = focus;
    if ((!o.screenshot.empty() || !o.checkpoint.empty() || !o.save_scene.empty() || o.orbit ||
         o.pick || o.zoom != 1.0) &&
        o.frames == 0) {
      throw drumlab::InputError(
          "--screenshot, --checkpoint, --save-scene, --orbit, --zoom and --pick need --frames N");
    }
    drumlab::gui::GuiApp gui(o);
    if (o.bench) {
      const auto b = gui.bench(bench_frames);
      const std::uint64_t steps = 300;
      const double cli = drumlab::gui::cli_particle_steps(o, steps);
      drumlab::gui::print_bench(o, b, bench_frames, cli, steps);
      return 0;
    }
    gui.run();
  } catch (const drumlab::InputError& e) {
    fmt::print(stderr, "drumlab-gui: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "drumlab-gui: failed: {}\n", e.what());
    return 1;
  }
  return 0;
}
