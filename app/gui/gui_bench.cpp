// drumlab-gui's headless run (--frames, with --orbit / --zoom / --pick) and --bench.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

#include "app/gui/gui_app.hpp"
#include "app/gui/gui_session.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/session/team_chooser.hpp"
#include "engine/threads.hpp"

namespace drumlab::gui {

void GuiApp::apply_view_flags() {
  if (options_.orbit) view_->orbit((*options_.orbit)[0], (*options_.orbit)[1]);
  if (options_.zoom != 1.0) view_->zoom(options_.zoom);
  if (!shown_ || (!options_.orbit && options_.zoom == 1.0 && !options_.pick)) return;
  const std::shared_ptr<const FrameSnapshot> s = shown_;
  frame();  // the view as turned, at full size (headless)
  render::DrumView& view = view_->drum_view();
  const auto axis = view.project(Vec3(0.0, 0.0, s->drum_depth));
  const auto back = view.project(Vec3::Zero());
  const auto rim = view.project(Vec3(0.0, s->drum_radius, s->drum_depth));
  fmt::print("view: front axis at ({:.1f}, {:.1f}), back axis at ({:.1f}, {:.1f}), rim {:.1f} px\n",
             axis[0], axis[1], back[0], back[1], std::hypot(rim[0] - axis[0], rim[1] - axis[1]));
  if (options_.pick) report_pick(*s, (*options_.pick)[0], (*options_.pick)[1]);
}

void GuiApp::report_layout(const FrameSnapshot& s) {
  const auto units = window_->window_size();
  const double scale = static_cast<double>(units[0]) / std::max(1, window_->width());  // per px
  const GuiWindow::ViewArea a = view_->area();
  fmt::print("layout            view {:.0f} 0 {:.0f} {}\n", a.x * scale, a.width * scale, units[1]);
  // The disk: the mantle's front and back rims as drawn (the image is the area's, at full size).
  render::DrumView& view = view_->drum_view();
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (int k = 0; k < 128; ++k) {
    const double phi = 2.0 * std::numbers::pi * k / 128.0;
    for (const double z : {0.0, s.drum_depth}) {
      const auto p =
          view.project(s.drum_radius * Vec3(std::cos(phi), std::sin(phi), 0.0) + Vec3(0.0, 0.0, z));
      x0 = std::min(x0, (p[0] + a.x) * scale);
      x1 = std::max(x1, (p[0] + a.x) * scale);
      y0 = std::min(y0, p[1] * scale);
      y1 = std::max(y1, p[1] * scale);
    }
  }
  fmt::print("layout            drum {:.0f} {:.0f} {:.0f} {:.0f}\n", x0, y0, x1 - x0, y1 - y0);
  for (const GuiWindow::PanelRect& p : GuiWindow::panels_shown()) {
    fmt::print("layout            panel {:.0f} {:.0f} {:.0f} {:.0f} {}\n", p.x, p.y, p.width,
               p.height, p.name);
  }
}

void GuiApp::report_pick(const FrameSnapshot& s, double x, double y) {
  // Every particle whose projected disc holds the pixel, and where the line of sight enters it,
  // from the projected pixels alone: an independent check that the pick is the front-most.
  render::DrumView& view = view_->drum_view();
  const auto [px, py] = view_->image_pixel(x, y, window_->window_size());
  const auto [near, far] = view.sight_line(px, py);
  const Vec3 d = (far - near).normalized();
  const auto entry = [&](std::size_t i) -> std::optional<double> {
    const auto c = view.project(s.position[i]);
    const auto e = view.project(s.position[i] + s.radius[i] * d.unitOrthogonal());
    const double r_px = std::hypot(e[0] - c[0], e[1] - c[1]);
    const double rho = s.radius[i] * std::hypot(c[0] - px, c[1] - py) / r_px;
    if (rho > s.radius[i]) return std::nullopt;
    return d.dot(s.position[i] - near) - std::sqrt(s.radius[i] * s.radius[i] - rho * rho);
  };
  std::size_t under = 0;
  double front = 1e300;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (const auto depth = entry(i)) {
      ++under;
      front = std::min(front, *depth);
    }
  }
  const std::uint64_t before = sim_->generation();
  const auto id = pick(x, y);
  // The focus is the snapshot's: wait for the one that carries it (the run has finished, so the
  // simulation thread answers the new wish at once), so the last frame shows it.
  for (int k = 0; id && sim_->generation() == before && k < 2000; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!id) {
    fmt::print("pick ({}, {}): none ({} particles under the cursor)\n", x, y, under);
    return;
  }
  const auto i = static_cast<std::size_t>(std::find(s.id.begin(), s.id.end(), *id) - s.id.begin());
  fmt::print(
      "pick ({}, {}): id {} entered at depth {:.9f} m; {} particles under the cursor, the "
      "front-most entered at depth {:.9f} m\n",
      x, y, *id, entry(i).value_or(-1.0), under, front);
}

void GuiApp::run() {
  if (options_.frames == 0) {
    while (!window_->should_close()) frame();
    return;
  }
  // Headless: at least `frames` UI frames, and until the simulation has made its steps.
  for (std::uint64_t k = 0; k < options_.frames || !sim_->finished(); ++k) {
    frame();
    if (sim_->state_text().starts_with("stopped")) {
      throw std::runtime_error(sim_->state_text());
    }
  }
  take_snapshot();
  apply_view_flags();
  frame(options_.screenshot);  // the last snapshot, panels included
  if (shown_ && !options_.screenshot.empty()) report_layout(*shown_);
  if (shown_) {  // the search's work since the start pins when a --switch-at happened
    const SearchCounters& t = shown_->totals;
    fmt::print(
        "search            {}; since the start: {} cells visited, {} pairs tested, {} found\n",
        shown_->search_name, t.cells_visited, t.pairs_tested, t.pairs_found);
    const std::string walk = teaching_.report(*shown_, shown_generation_);
    if (!walk.empty()) fmt::print("{}\n", walk);
  }
  if (!options_.save_scene.empty()) scene_editor_->save(options_.save_scene);
  if (!options_.checkpoint.empty()) {
    const std::string file = options_.checkpoint;
    sim_->with_simulation(
        [&](const Simulation& sim) { write_checkpoint(file, sim.state(), sim.scene().name); });
  }
  if (const std::optional<TeamChooser> t = sim_->team()) {
    fmt::print("team              {}\n", team_report(*t));
  }
}

BenchFigures GuiApp::bench(std::uint64_t frames) {
  BenchFigures b;
  b.max_running_fps = clock_.max_running_fps;
  // Settle first (drawing as it goes), then pause: both measurements on the settled bed.
  sim_->set_running(true);
  while (!sim_->settled()) {
    if (sim_->state_text().starts_with("stopped")) throw std::runtime_error(sim_->state_text());
    frame();
  }
  sim_->set_running(false);
  while (sim_->running()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  frame();
  profiling_ = true;
  // Paused, the camera orbiting: the drawing alone (reduced while it moves).
  profile_ = {};
  double t0 = now_seconds();
  for (std::uint64_t k = 0; k < frames; ++k) {
    view_->orbit(360.0 / static_cast<double>(frames), 0.0);
    frame();
  }
  b.paused_fps = static_cast<double>(frames) / (now_seconds() - t0);
  b.orbiting = profile_;
  // Paused, the camera still: full size, once; then the image shown again.
  view_->place_camera();
  t0 = now_seconds();
  profile_ = {};
  for (std::uint64_t k = 0; k < frames; ++k) frame();
  b.still_fps = static_cast<double>(frames) / (now_seconds() - t0);
  b.still = profile_;
  // Running: paced as in the window (at most max_running_fps frames/s).
  const auto [steps0, seconds0] = sim_->stepping_totals();
  profile_ = {};
  sim_->set_running(true);
  t0 = now_seconds();
  for (std::uint64_t k = 0; k < frames; ++k) frame();
  const double wall = now_seconds() - t0;
  b.running_fps = static_cast<double>(frames) / wall;
  b.running = profile_;
  b.running_pictures = static_cast<double>(profile_.renders) / wall;
  sim_->set_running(false);
  while (sim_->running()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const auto [steps1, seconds1] = sim_->stepping_totals();
  b.gui_particle_steps = seconds1 > seconds0 ? (steps1 - steps0) / (seconds1 - seconds0) : 0.0;
  b.gui_wall_particle_steps = (steps1 - steps0) / wall;
  b.gui_steps = steps1 - steps0;
  profiling_ = false;
  return b;
}

double cli_particle_steps(const GuiOptions& o, std::uint64_t steps) {
  set_thread_count(1);
  RunSession session(gui_scene(o.scene), session_options(o));
  session.settle();
  const auto t0 = std::chrono::steady_clock::now();
  session.advance(steps);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return static_cast<double>(session.simulation().particles().size()) * static_cast<double>(steps) /
         s;
}

namespace {

void print_split(const char* what, const FrameProfile& p) {
  const double n = std::max<double>(1.0, static_cast<double>(p.frames));
  const double factor =
      static_cast<double>(p.reduction_sum) / std::max<double>(1.0, static_cast<double>(p.renders));
  fmt::print(
      "  {} ms/frame: panels {:.1f}, view render {:.1f} ({} of {} frames rendered, mean image "
      "reduction {:.2f}), inset {:.1f}, show {:.1f}, ImGui {:.1f}, swap {:.1f}, paced wait "
      "{:.1f}\n",
      what, 1e3 * p.panels / n, 1e3 * p.view / n, p.renders, p.frames, factor, 1e3 * p.inset / n,
      1e3 * p.show / n, 1e3 * p.imgui / n, 1e3 * p.swap / n, 1e3 * p.wait / n);
}

}  // namespace

void print_bench(const GuiOptions& o, const BenchFigures& b, std::uint64_t frames, double cli,
                 std::uint64_t cli_steps) {
  fmt::print("drumlab-gui --bench: {} ({} frames each, window {} x {})\n", o.scene, frames, o.width,
             o.height);
  fmt::print("  frames/s paused (orbiting; the view reduced while it moves, for 30/s): {:.1f}\n",
             b.paused_fps);
  fmt::print("  frames/s paused (still, full size, the image shown again):   {:.1f}\n",
             b.still_fps);
  fmt::print("  frames/s running (paced, at most {:.0f}/s): {:.1f}, new snapshots drawn/s {:.1f}\n",
             b.max_running_fps, b.running_fps, b.running_pictures);
  print_split("orbiting", b.orbiting);
  print_split("still   ", b.still);
  print_split("running ", b.running);
  fmt::print(
      "  particle-steps/s in the GUI (stepping time on its thread): {:.3g}; per wall second "
      "while running: {:.3g}\n",
      b.gui_particle_steps, b.gui_wall_particle_steps);
  fmt::print(
      "  particle-steps/s CLI-equivalent (1 thread, no window, {} steps, same process): "
      "{:.3g}\n",
      cli_steps, cli);
  fmt::print("  GUI / CLI: {:.0f} % (stepping time), {:.0f} % (wall)\n",
             100.0 * b.gui_particle_steps / cli, 100.0 * b.gui_wall_particle_steps / cli);
}

}  // namespace drumlab::gui
