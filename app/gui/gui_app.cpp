#include "app/gui/gui_app.hpp"

#include "app/gui/gui_session.hpp"
#include "engine/threads.hpp"

namespace drumlab::gui {

namespace {

/// Checks --method and sets the UI thread's OpenMP threads (before anything else is built).
const GuiOptions& checked_flags(const GuiOptions& options) {
  if (!options.method.empty()) check_method(options.method, "--method");
  set_thread_count(options.threads);
  return options;
}

/// The view options of the flags; --focus auto resolved on the filled scene (before the thread
/// starts).
render::ViewOptions initial_view(const GuiOptions& options, const SceneConfig& scene) {
  render::ViewOptions v;
  v.width = options.width;
  v.height = options.height;
  v.color_by = render::parse_color_by(options.color_by);
  v.camera = render::parse_camera(options.camera);
  v.focus_id = options.focus_id;
  v.text = false;  // the panels show the figures the picture's text would
  v.zoom_to_focus = options.zoom_to_focus;
  if (options.focus == "auto") {
    RunSession probe(scene, session_options(options));
    v.focus_id = render::auto_focus_id(probe.simulation().particles());
  }
  return v;
}

}  // namespace

GuiApp::GuiApp(const GuiOptions& options) : options_(checked_flags(options)), teaching_(options) {
  const SceneConfig scene = gui_scene(options.scene);
  render::ViewOptions view = initial_view(options, scene);
  SnapshotWish wish;
  wish.view = view;
  if (teaching_.on()) wish.compare_methods = teaching_.compare_methods(true);
  const std::uint64_t limit = options.frames > 0 ? options.frames * options.steps_per_frame : 0;
  sim_ = std::make_unique<SimThread>(scene, session_options(options), wish, options.threads,
                                     options.switch_at, limit);
  sim_->set_chunk(options.steps_per_frame);
  scene_editor_.emplace(options.scene, options.edits);
  search_.emplace(sim_->scene().search_method);

  window_ = std::make_unique<GuiWindow>(options.width, options.height,
                                        !(options.frames > 0 || options.bench));
  view.width = window_->view_area().width;
  view.height = window_->height();
  view_ = std::make_unique<MainView>(*window_, view);
  inset_ = std::make_unique<FocusInset>(*window_, options.inset);
  if (options.frames > 0 || options.bench) sim_->set_running(options.frames > 0);
  clock_.start(now_seconds());
}

GuiApp::~GuiApp() {
  sim_.reset();  // stop the simulation first
}

void GuiApp::set_view_options(const render::ViewOptions& o) {
  view_->set_options(o);
  push_wish();
}

void GuiApp::push_wish() {
  SnapshotWish wish;
  wish.view = view_->options();
  wish.compare_methods = teaching_.compare_methods(view_->options().focus_id.has_value());
  sim_->set_wish(std::move(wish));
}

FrameSnapshot GuiApp::drawn(const FrameSnapshot& s) {
  return teaching_.display_snapshot(s, shown_generation_);
}

}  // namespace drumlab::gui
