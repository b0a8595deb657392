// drumlab-gui: the interactive workbench (GLFW + Dear ImGui + the VTK drum view). Headless driving
// for tests and benchmarks: --frames N --screenshot FILE.png, --bench. Exit codes: 0 success,
// 2 bad input (one line), 1 anything else (no display, a failed run).
#include <chrono>
#include <cstdio>
#include <exception>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/gui/gui_app.hpp"
#include "app/gui/gui_options.hpp"
#include "engine/session/run_session.hpp"
#include "engine/threads.hpp"

namespace {

/// The CLI-equivalent run: the same scene and options in one RunSession, one thread, no window;
/// particle-steps per second of `steps` turning steps.
double cli_particle_steps(const drumlab::gui::GuiOptions& o, std::uint64_t steps) {
  drumlab::SessionOptions so;
  so.scene_file = o.scene;
  so.method = o.method;
  so.settle_time = o.settle_time;
  drumlab::set_thread_count(1);
  drumlab::RunSession session(drumlab::gui::gui_scene(o.scene), so);
  session.settle();
  const auto t0 = std::chrono::steady_clock::now();
  session.advance(steps);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return static_cast<double>(session.simulation().particles().size()) * static_cast<double>(steps) /
         s;
}

}  // namespace

int main(int argc, char** argv) {
  drumlab::gui::GuiOptions o;
  o.scene = DRUMLAB_SCENES_DIR "/drum_demo.toml";
  std::string switch_at, focus;
  std::uint64_t bench_frames = 100;
  CLI::App app{"drumlab-gui: the drum workbench (run under xvfb-run for headless use)"};
  app.add_option("scene", o.scene, "scene file (default: scenes/drum_demo.toml)");
  app.add_option("--method", o.method,
                 "search method (auto, brute, m1..m5, mlgrid, verlet[:GRID])");
  app.add_option("--focus", focus, "stable id of the particle whose search is shown, or auto");
  app.add_option("--switch-at", switch_at, "K:METHOD: switch the search after K turning steps");
  app.add_option("--color-by", o.color_by, "size, speed, omega, id, coordination, ...");
  app.add_option("--camera", o.camera, "axis or iso");
  app.add_option("--settle-time", o.settle_time, "s with the drum at rest first (default: scene)");
  app.add_option("--steps-per-frame", o.steps_per_frame, "simulation steps per snapshot")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000}));
  app.add_option("--threads", o.threads, "simulation threads")->check(CLI::Range(1, 256));
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
    if (!focus.empty() && focus != "auto") {
      std::size_t end = 0;
      unsigned long id = 0;
      try {
        id = std::stoul(focus, &end);
      } catch (const std::exception&) {
        end = 0;
      }
      if (end != focus.size()) {
        throw drumlab::InputError(fmt::format("--focus: '{}' is neither an id nor auto", focus));
      }
      o.focus_id = static_cast<drumlab::Index>(id);
    }
    o.focus = focus;
    if ((!o.screenshot.empty() || !o.checkpoint.empty() || !o.save_scene.empty()) &&
        o.frames == 0) {
      throw drumlab::InputError("--screenshot, --checkpoint and --save-scene need --frames N");
    }
    drumlab::gui::GuiApp gui(o);
    if (o.bench) {
      const auto b = gui.bench(bench_frames);
      const std::uint64_t steps = 300;
      const double cli = cli_particle_steps(o, steps);
      fmt::print("drumlab-gui --bench: {} ({} frames each)\n", o.scene, bench_frames);
      fmt::print("  frames/s paused (orbiting): {:.1f}\n", b.paused_fps);
      fmt::print("  frames/s running:           {:.1f}\n", b.running_fps);
      fmt::print("  particle-steps/s in the GUI:        {:.3g}\n", b.gui_particle_steps);
      fmt::print("  particle-steps/s CLI-equivalent (1 thread, no window, {} steps): {:.3g}\n",
                 steps, cli);
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
