// The workbench's frame loop: pacing, the newest snapshot, the panels, the view rendered only
// when something changed (MainView), the focus inset, and the mouse (orbit, zoom, pick).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <thread>

#include <imgui.h>
// clang-format off
#include <backends/imgui_impl_opengl3.h>
#include <GLFW/glfw3.h>
// clang-format on

#include "app/gui/gui_app.hpp"
#include "app/gui/gui_session.hpp"

namespace drumlab::gui {

namespace {

/// Seconds since `t0`, after glFinish() when measuring (so the GL work is charged to its part).
double lap(double& t0, bool finish) {
  if (finish) glFinish();
  const double t = now_seconds();
  const double d = t - t0;
  t0 = t;
  return d;
}

}  // namespace

void GuiApp::pace() {
  if (options_.frames > 0) {  // headless: as fast as it goes
    glfwPollEvents();
    return;
  }
  if (sim_->running()) {
    const double wait = clock_.last_frame + 1.0 / clock_.max_running_fps - now_seconds();
    if (wait > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
    // No faster than new snapshots arrive (the input is still read 10 times a second).
    const double until = now_seconds() + 0.1;
    glfwPollEvents();
    while (sim_->running() && sim_->generation() == shown_generation_ && !view_->camera_dirty() &&
           !mouse_.dragging() && now_seconds() < until) {
      glfwWaitEventsTimeout(0.005);
    }
    return;
  }
  const bool idle = view_->still() && sim_->generation() == shown_generation_ &&
                    !mouse_.dragging() && !options_.bench;
  if (idle) {
    glfwWaitEventsTimeout(0.05);  // nothing to draw: wake for input or a new snapshot
  } else {
    glfwPollEvents();
  }
}

void GuiApp::take_snapshot() {
  const std::uint64_t gen = sim_->generation();
  if (gen == shown_generation_ && shown_) return;
  shown_ = sim_->latest();
  shown_generation_ = gen;
  if (shown_) search_->add(*shown_);
}

void GuiApp::panels() {
  window_->begin_frame();
  const FrameSnapshot* s = shown_.get();
  panel_run();
  scene_editor_->panel(*window_, *sim_);
  search_->panel(*window_, *sim_, s);
  panel_view(s);
  export_.panel(*window_, *sim_, s);
  if (teaching_.panel(*window_, s, shown_generation_, view_->options().focus_id,
                      clock_.last_frame)) {
    push_wish();
  }
  inset_->panel(view_->options().focus_id);
  handle_mouse();
  ImGui::Render();
  if (window_->track_size()) view_->set_window_size(window_->width(), window_->height());
}

void GuiApp::render(bool full, double& t0) {
  const FrameSnapshot& s = *shown_;
  const auto as_drawn = [this](const FrameSnapshot& f) { return drawn(f); };
  try {
    const bool teaching = teaching_.on() && s.focus_index && !s.compare_visits.empty();
    const MainView::Rendered r = view_->render(s, shown_generation_, teaching_.key(), teaching,
                                               full, sim_->running(), as_drawn);
    if (r.scene) inset_->mark_dirty();
    if (r.factor > 0) {
      ++profile_.renders;
      profile_.reduction_sum += r.factor;
    }
  } catch (const InputError& e) {  // e.g. occupancy asked of a method without a grid
    render::ViewOptions o = view_->options();
    o.grid = false;
    view_->set_options(o);
    export_.set_message(e.what());
  }
  profile_.view += lap(t0, profiling_);
  inset_->render(s, view_->drawn_generation(), view_->options(), as_drawn);
  profile_.inset += lap(t0, profiling_);
  export_.take(*view_, shown_generation_);
}

void GuiApp::frame(const std::string& grab) {
  double t0 = now_seconds();
  pace();
  const double frame_start = now_seconds();
  take_snapshot();
  clock_.tick(now_seconds());
  profile_.wait += lap(t0, false);
  panels();
  profile_.panels += lap(t0, false);
  if (shown_) {
    render(!grab.empty() || export_.wants_full_view() || options_.frames > 0, t0);
  }
  ViewImage::bind_window();
  glViewport(0, 0, window_->width(), window_->height());
  if (shown_) {
    view_->show();
  } else {
    glClearColor(0.11f, 0.12f, 0.15f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  profile_.show += lap(t0, profiling_);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!grab.empty()) {  // the whole window, panels included
    render::CurrentGlContext window(window_->width(), window_->height());
    render::write_png(window.read_image(), grab);
  }
  profile_.imgui += lap(t0, profiling_);
  glfwSwapBuffers(window_->glfw());
  profile_.swap += lap(t0, profiling_);
  ++profile_.frames;
  view_->adapt_reduction(now_seconds() - frame_start);
}

std::optional<Index> GuiApp::pick(double x, double y) {
  if (!shown_) return std::nullopt;
  const auto id = view_->pick(*shown_, x, y, window_->window_size());
  if (!id) return std::nullopt;
  render::ViewOptions o = view_->options();
  o.focus_id = id;
  teaching_.show_whole_search();
  set_view_options(o);
  return id;
}

void GuiApp::handle_mouse() {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_->glfw(), &x, &y);
  if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) mouse_.press(x, y);
  if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    if (const auto move = mouse_.hold(x, y)) view_->orbit(-0.4 * (*move)[0], 0.4 * (*move)[1]);
  }
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && mouse_.release()) pick(x, y);
  if (io.MouseWheel != 0.0f) view_->zoom(std::pow(1.1, io.MouseWheel));
}

}  // namespace drumlab::gui
