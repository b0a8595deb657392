#include "app/gui/gui_app.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <imgui.h>
// clang-format off
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <GLFW/glfw3.h>
// clang-format on

#include "engine/io/checkpoint.hpp"
#include "engine/scene/scene_writer.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/threads.hpp"

namespace drumlab::gui {

void History::add(double v, std::size_t keep) {
  values.push_back(static_cast<float>(v));
  while (values.size() > keep) values.pop_front();
}

namespace {

std::vector<std::string> all_methods() {
  std::vector<std::string> names = search_method_names();
  for (const std::string& b : verlet_builder_names()) {
    const std::string v = verlet_method_name(b);
    if (std::find(names.begin(), names.end(), v) == names.end()) names.push_back(v);
  }
  names.emplace_back("auto");
  return names;
}

}  // namespace

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

SessionOptions session_options(const GuiOptions& o) {
  SessionOptions s;
  s.scene_file = o.scene;
  s.method = o.method;
  s.settle_time = o.settle_time;
  s.adaptive_team = o.team == "adaptive";
  return s;
}

SceneConfig gui_scene(const std::string& file) {
  return with_gui_checks(load_dynamic_scene(file));
}

SceneConfig with_gui_checks(SceneConfig scene) {
  scene.output.diagnostics_every = std::min<std::uint64_t>(scene.output.diagnostics_every, 50);
  return scene;
}

GuiApp::GuiApp(const GuiOptions& options) : options_(options), methods_(all_methods()) {
  view_options_.width = options.width;
  view_options_.height = options.height;
  view_options_.color_by = render::parse_color_by(options.color_by);
  view_options_.camera = render::parse_camera(options.camera);
  view_options_.focus_id = options.focus_id;
  view_options_.text = false;  // the panels show the figures the picture's text would
  if (!options.method.empty()) check_method(options.method, "--method");
  set_thread_count(options.threads);
  teach_methods_ = cell_grid_method_names();
  teach_ = options.teach;
  view_options_.zoom_to_focus = options.zoom_to_focus;
  if (!options.teach_method.empty()) {
    const auto t = std::find(teach_methods_.begin(), teach_methods_.end(), options.teach_method);
    if (t == teach_methods_.end()) {
      throw InputError(fmt::format("--teach-method: '{}' is not one of {}", options.teach_method,
                                   fmt::join(teach_methods_, ", ")));
    }
    teach_method_ = static_cast<int>(t - teach_methods_.begin());
  }
  if (options.teach_cells >= 0) teach_step_ = options.teach_cells;

  SnapshotWish wish;
  wish.view = view_options_;
  if (teach_) wish.compare_methods = teach_methods_;
  const std::uint64_t limit = options.frames > 0 ? options.frames * options.steps_per_frame : 0;
  SceneConfig scene = gui_scene(options.scene);
  if (options.focus == "auto") {  // resolved on the filled scene, before the thread starts
    RunSession probe(scene, session_options(options));
    view_options_.focus_id = render::auto_focus_id(probe.simulation().particles());
    wish.view.focus_id = view_options_.focus_id;
  }
  sim_ = std::make_unique<SimThread>(scene, session_options(options), wish, options.threads,
                                     options.switch_at, limit);
  sim_->set_chunk(options.steps_per_frame);
  edited_ = load_dynamic_scene(options.scene);  // the file's scene, not the GUI's run of it
  for (const std::string& e : options.edits) apply_edit(edited_, e);
  const auto it = std::find(methods_.begin(), methods_.end(), sim_->scene().search_method);
  method_index_ = it == methods_.end() ? 0 : static_cast<int>(it - methods_.begin());

  if (glfwInit() != GLFW_TRUE) {
    throw std::runtime_error("no display for the window (set DISPLAY, or run under xvfb-run)");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 2);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(options.width, options.height, "drumlab-gui", nullptr, nullptr);
  if (window_ == nullptr) {
    glfwTerminate();
    throw std::runtime_error("could not open an OpenGL 3.2 core window");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(options.frames > 0 || options.bench ? 0 : 1);
  glfwGetFramebufferSize(window_, &fb_w_, &fb_h_);
  view_options_.width = fb_w_;
  view_options_.height = fb_h_;

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout is the program's, not a file's
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 150");

  GLFWwindow* w = window_;
  image_.resize(fb_w_, fb_h_);
  target_ = std::make_unique<render::CurrentGlContext>(fb_w_, fb_h_, [w, this] {
    glfwMakeContextCurrent(w);
    image_.bind();
  });
  view_ = std::make_unique<render::DrumView>(view_options_, *target_);
  inset_on_ = options.inset;
  if (options.frames > 0 || options.bench) sim_->set_running(options.frames > 0);
  last_frame_time_ = fps_since_ = now_seconds();
}

GuiApp::~GuiApp() {
  sim_.reset();  // stop the simulation first
  inset_.reset();
  view_.reset();
  if (window_ != nullptr) {
    glfwMakeContextCurrent(window_);
    image_.release();
    inset_image_.release();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
}

void GuiApp::save_edited_scene(const std::string& file) {
  save_scene(edited_, file);
}

void GuiApp::push_view_options() {
  view_->set_options(view_options_);
  view_dirty_ = true;
  push_wish();
}

void GuiApp::push_wish() {
  SnapshotWish wish;
  wish.view = view_options_;
  if (teach_ && view_options_.focus_id) wish.compare_methods = teach_methods_;
  sim_->set_wish(std::move(wish));
}

void GuiApp::update_history(const FrameSnapshot& s) {
  if (s.steps == last_history_step_) return;
  last_history_step_ = s.steps;
  const double n = std::max<double>(1.0, static_cast<double>(s.size()));
  cells_per_particle_.add(static_cast<double>(s.counters.cells_visited) / n);
  tests_per_particle_.add(static_cast<double>(s.counters.pairs_tested) / n);
  contacts_per_particle_.add(static_cast<double>(s.counters.pairs_found) / n);
  if (s.diagnostics) kinetic_.add(s.diagnostics->kinetic_energy);
  if (s.steps > last_timer_steps_) {
    const double steps = static_cast<double>(s.steps - last_timer_steps_);
    recent_split_.search = s.timers.search - last_timers_.search;
    recent_split_.forces = s.timers.forces - last_timers_.forces;
    recent_split_.walls = s.timers.walls - last_timers_.walls;
    recent_split_.integration = s.timers.integration - last_timers_.integration;
    recent_split_.reorder = s.timers.reorder - last_timers_.reorder;
    if (last_timer_steps_ > 0) step_ms_.add(1000.0 * recent_split_.total() / steps);
  }
  last_timers_ = s.timers;
  last_timer_steps_ = s.steps;
}

FrameSnapshot GuiApp::display_snapshot(const FrameSnapshot& s) {
  if (!teach_ || !s.focus_index || s.compare_visits.empty()) return s;
  teach_method_ = std::clamp(teach_method_, 0, static_cast<int>(s.compare_visits.size()) - 1);
  const MethodVisit& mv = s.compare_visits[static_cast<std::size_t>(teach_method_)];
  if (!walk_ || walk_generation_ != shown_generation_ || walk_method_ != teach_method_) {
    walk_.emplace(mv.visit, s.position);
    walk_generation_ = shown_generation_;
    walk_method_ = teach_method_;
  }
  FrameSnapshot d = s;
  teach_step_ = std::min(teach_step_, static_cast<int>(walk_->steps()));
  d.focus_visit = walk_->prefix(static_cast<std::size_t>(teach_step_));
  if (!mv.visit.grids.empty()) d.grid = mv.visit.grids.front().geometry;
  d.search_name = mv.method + " (teaching)";
  return d;
}

}  // namespace drumlab::gui
