#include "app/gui/gui_command_line.hpp"

#include <array>
#include <charconv>
#include <limits>

#include "app/run/count_option.hpp"
#include "engine/types.hpp"

namespace drumlab::gui {

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
                 "headless: run N frames (steps-per-frame steps each), exit")
      ->check(drumlab::cli::whole_count());
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
  app.add_option("--bench-frames", c.bench_frames, "frames per --bench measurement")
      ->check(drumlab::cli::whole_count());
}

void finish_options(CommandLine& c) {
  GuiOptions& o = c.o;
  if (!c.switch_at.empty()) o.switch_at = parse_switch_at(c.switch_at);
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

}  // namespace drumlab::gui
