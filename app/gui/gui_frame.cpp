// The workbench's frame loop: pacing, the view rendered into its image only when something
// changed (at a reduced size while the camera moves), the focus inset, the mouse (orbit, zoom,
// pick) and the headless run.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <thread>

#include <fmt/format.h>
#include <imgui.h>
// clang-format off
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <GLFW/glfw3.h>
// clang-format on

#include "app/gui/gui_app.hpp"
#include "engine/io/checkpoint.hpp"

namespace drumlab::gui {

namespace {

/// The camera counts as still this long after its last move: then the view is rendered at full
/// size again.
constexpr double kStillSeconds = 0.25;
/// The frame rate a moving view aims at (the image reduction adapts to it), and the largest
/// reduction it may use.
constexpr double kInteractiveFps = 30.0;
constexpr int kMaxReduction = 4;

/// Seconds since `t0`, after glFinish() when measuring (so the GL work is charged to its part).
double lap(double& t0, bool finish) {
  if (finish) glFinish();
  const double t = now_seconds();
  const double d = t - t0;
  t0 = t;
  return d;
}

}  // namespace

void GuiApp::camera_changed(bool reset) {
  if (reset) view_->reset_camera();
  camera_moved_at_ = now_seconds();
  camera_dirty_ = true;
}

void GuiApp::pace() {
  if (options_.frames > 0) {  // headless: as fast as it goes
    glfwPollEvents();
    return;
  }
  if (sim_->running()) {
    const double wait = last_frame_time_ + 1.0 / max_running_fps_ - now_seconds();
    if (wait > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
    // No faster than new snapshots arrive (the input is still read 10 times a second).
    const double until = now_seconds() + 0.1;
    glfwPollEvents();
    while (sim_->running() && sim_->generation() == shown_generation_ && !camera_dirty_ &&
           !dragging_ && now_seconds() < until) {
      glfwWaitEventsTimeout(0.005);
    }
    return;
  }
  const bool still = now_seconds() - camera_moved_at_ > kStillSeconds;
  const bool idle = !camera_dirty_ && still && image_.width() == fb_w_ &&
                    sim_->generation() == shown_generation_ && !dragging_ && !options_.bench;
  if (idle) {
    glfwWaitEventsTimeout(0.05);  // nothing to draw: wake for input or a new snapshot
  } else {
    glfwPollEvents();
  }
}

int GuiApp::reduction_now(bool full) const {
  const bool moving = now_seconds() - camera_moved_at_ < kStillSeconds;
  if (full || !(moving || (reduce_running_ && sim_->running()))) return 1;
  return auto_reduction_ ? adaptive_reduction_ : std::max(1, reduction_);
}

void GuiApp::adapt_reduction(int used, double seconds) {
  // VTK's desired update rate for interaction: the factor that keeps a moving frame within
  // 1 / kInteractiveFps s (pixels scale as 1 / factor^2).
  if (used == 1 || !auto_reduction_) return;
  const double budget = 1.0 / kInteractiveFps;
  if (seconds > budget && adaptive_reduction_ < kMaxReduction) ++adaptive_reduction_;
  if (seconds < 0.3 * budget && adaptive_reduction_ > 2) --adaptive_reduction_;
}

void GuiApp::render_view(const FrameSnapshot& s, bool full) {
  const int f = reduction_now(full);
  const int w = std::max(1, fb_w_ / f), h = std::max(1, fb_h_ / f);
  const bool teaching = teach_ && s.focus_index && !s.compare_visits.empty();
  const bool new_snapshot = shown_generation_ != drawn_generation_;
  const bool new_scene =
      new_snapshot || view_dirty_ ||
      (teaching && drawn_teach_ != std::pair<int, int>{teach_method_, teach_step_});
  if (!new_scene && !camera_dirty_ && w == image_.width() && h == image_.height()) return;
  glfwMakeContextCurrent(window_);
  image_.resize(w, h);
  target_->resize(w, h);
  view_->set_size(w, h);
  if (view_options_.zoom_to_focus && new_snapshot) view_->reset_camera();  // follow the focus
  if (new_scene) {
    view_->draw(display_snapshot(s));
    drawn_generation_ = shown_generation_;
    drawn_teach_ = {teach_method_, teach_step_};
    view_dirty_ = false;
    inset_dirty_ = true;
  } else {
    view_->redraw();
  }
  camera_dirty_ = false;
  ++profile_.renders;
  profile_.reduction_sum += f;
}

void GuiApp::frame(const std::string& grab) {
  double t0 = now_seconds();
  pace();
  const double frame_start = now_seconds();
  const std::uint64_t gen = sim_->generation();
  if (gen != shown_generation_ || !shown_) {
    shown_ = sim_->latest();
    shown_generation_ = gen;
    if (shown_) update_history(*shown_);
  }
  const double t = now_seconds();
  ++frames_counted_;
  if (t - fps_since_ >= 0.5) {  // frames per second over the last half second or more
    fps_ = static_cast<double>(frames_counted_) / (t - fps_since_);
    fps_since_ = t;
    frames_counted_ = 0;
  }
  last_frame_time_ = t;
  profile_.wait += lap(t0, false);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  const FrameSnapshot* s = shown_.get();
  panel_run();
  panel_scene();
  panel_search(s);
  panel_view(s);
  panel_export(s);
  panel_teach(s);
  panel_inset();
  handle_mouse();
  ImGui::Render();
  relayout_ = false;
  int fb_w = 0, fb_h = 0;
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  if (fb_w > 0 && fb_h > 0 && (fb_w != fb_w_ || fb_h != fb_h_)) {  // the window was resized
    fb_w_ = fb_w;
    fb_h_ = fb_h;
    relayout_ = true;
  }
  profile_.panels += lap(t0, false);

  const bool full = !grab.empty() || grab_view_ || movie_frames_ || options_.frames > 0;
  if (s != nullptr) {
    try {
      render_view(*s, full);
    } catch (const InputError& e) {  // e.g. occupancy asked of a method without a grid
      view_options_.grid = false;
      view_->set_options(view_options_);
      view_dirty_ = true;
      export_message_ = e.what();
    }
    profile_.view += lap(t0, profiling_);
    render_inset(*s);
    profile_.inset += lap(t0, profiling_);
    if (grab_view_) {  // the view alone, without the panels
      grab_view_ = false;
      try {
        target_->make_current();
        render::write_png(target_->read_image(), png_path_);
        export_message_ = fmt::format("wrote {}", png_path_);
      } catch (const std::exception& e) {
        export_message_ = e.what();
      }
    }
    if (movie_frames_ && shown_generation_ != movie_last_generation_) {
      movie_last_generation_ = shown_generation_;
      target_->make_current();
      movie_frames_->write(target_->read_image(), movie_frames_->frames_written());
    }
  }
  ViewImage::bind_window();
  glViewport(0, 0, fb_w_, fb_h_);
  if (s != nullptr) {
    image_.show(fb_w_, fb_h_);  // covers the window: no clear
  } else {
    glClearColor(0.11f, 0.12f, 0.15f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  profile_.show += lap(t0, profiling_);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!grab.empty()) {  // the whole window, panels included
    render::CurrentGlContext window(fb_w_, fb_h_);
    render::write_png(window.read_image(), grab);
  }
  profile_.imgui += lap(t0, profiling_);
  glfwSwapBuffers(window_);
  profile_.swap += lap(t0, profiling_);
  ++profile_.frames;
  adapt_reduction(image_.width() < fb_w_ ? fb_w_ / std::max(1, image_.width()) : 1,
                  now_seconds() - frame_start);
}

void GuiApp::render_inset(const FrameSnapshot& s) {
  if (!inset_on_ || !view_options_.focus_id || !s.focus_visit) return;
  if (!inset_dirty_ && inset_generation_ == drawn_generation_) return;
  glfwMakeContextCurrent(window_);
  if (!inset_) {
    inset_image_.resize(inset_size_, inset_size_);
    GLFWwindow* w = window_;
    inset_target_ = std::make_unique<render::CurrentGlContext>(inset_size_, inset_size_, [w, this] {
      glfwMakeContextCurrent(w);
      inset_image_.bind();
    });
    render::ViewOptions o = view_options_;
    o.width = o.height = inset_size_;
    o.overlay = false;  // the main view has the legend
    inset_ = std::make_unique<render::DrumView>(o, *inset_target_);
  }
  render::ViewOptions o = view_options_;
  o.zoom_to_focus = true;
  o.overlay = false;
  o.walls = false;
  inset_->set_options(o);
  inset_->reset_camera();  // follow the focus particle
  inset_->draw(display_snapshot(s));
  inset_generation_ = drawn_generation_;
  inset_dirty_ = false;
}

void GuiApp::panel_inset() {
  if (!inset_ || !inset_on_ || !view_options_.focus_id) return;
  const auto edge = -static_cast<float>(inset_size_) - 20.0f;
  place(edge - 370.0f, edge - 40.0f, 0);  // bottom right, beside the Export panel
  ImGui::Begin("Focus inset", &inset_on_, ImGuiWindowFlags_AlwaysAutoResize);
  const auto size = static_cast<float>(inset_size_);
  // The texture's rows run bottom to top: flip it.
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(inset_image_.texture())),
               ImVec2(size, size), ImVec2(0, 1), ImVec2(1, 0));
  ImGui::TextDisabled("focus %u, its search framed",
                      static_cast<unsigned>(*view_options_.focus_id));
  ImGui::End();
}

std::optional<Index> GuiApp::pick(double x, double y) {
  if (!shown_ || image_.width() == 0) return std::nullopt;
  const FrameSnapshot& s = *shown_;
  int win_w = 0, win_h = 0;  // cursor positions are in window units, the image in pixels
  glfwGetWindowSize(window_, &win_w, &win_h);
  const double px = x * image_.width() / std::max(1, win_w);
  const double py = y * image_.height() / std::max(1, win_h);
  const auto [near, far] = view_->sight_line(px, py);
  const auto hit = render::first_sphere_hit(near, far, s.position, s.radius);
  if (!hit) return std::nullopt;
  view_options_.focus_id = s.id[*hit];
  teach_step_ = 1 << 30;
  push_view_options();
  return view_options_.focus_id;
}

void GuiApp::handle_mouse() {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_, &x, &y);
  if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    dragging_ = false;
    press_x_ = last_x_ = x;
    press_y_ = last_y_ = y;
  }
  if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    if (std::hypot(x - press_x_, y - press_y_) > 4.0) dragging_ = true;
    if (dragging_ && (x != last_x_ || y != last_y_)) {
      view_->orbit(-0.4 * (x - last_x_), 0.4 * (y - last_y_));
      camera_changed();
    }
    last_x_ = x;
    last_y_ = y;
  }
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left)) {
    if (!dragging_) pick(x, y);
    dragging_ = false;
  }
  if (io.MouseWheel != 0.0f) {
    view_->zoom(std::pow(1.1, io.MouseWheel));
    camera_changed();
  }
}

}  // namespace drumlab::gui
