#include "app/gui/main_view.hpp"

#include <algorithm>

#include <GL/gl.h>

#include "app/gui/gui_session.hpp"
#include "app/gui/gui_window.hpp"

namespace drumlab::gui {

namespace {

/// The camera counts as still this long after its last move: then the view is rendered at full
/// size again.
constexpr double kStillSeconds = 0.25;

}  // namespace

MainView::MainView(const GuiWindow& window, render::ViewOptions options)
    : window_(window),
      options_(std::move(options)),
      fb_w_(window.view_area().width),
      fb_h_(window.height()),
      area_x_(window.view_area().x),
      window_w_(window.width()) {
  image_.resize(fb_w_, fb_h_);
  target_ = std::make_unique<render::CurrentGlContext>(fb_w_, fb_h_, [this] {
    window_.make_current();
    image_.bind();
  });
  view_ = std::make_unique<render::DrumView>(options_, *target_);
}

MainView::~MainView() {
  view_.reset();
  window_.make_current();
  image_.release();
}

void MainView::set_options(const render::ViewOptions& options) {
  options_ = options;
  view_->set_options(options_);
  options_dirty_ = true;
}

void MainView::camera_changed(bool reset) {
  if (reset) view_->reset_camera();
  camera_moved_at_ = now_seconds();
  camera_dirty_ = true;
}

void MainView::orbit(double azimuth_deg, double elevation_deg) {
  view_->orbit(azimuth_deg, elevation_deg);
  camera_changed();
}

void MainView::zoom(double factor) {
  view_->zoom(factor);
  camera_changed();
}

void MainView::place_camera() {
  camera_changed(true);
  camera_moved_at_ = -1e9;
}

void MainView::set_camera_mode(render::CameraMode mode) {
  options_.camera = mode;
  view_->set_options(options_);
  camera_changed(true);
}

bool MainView::moving() const {
  return now_seconds() - camera_moved_at_ < kStillSeconds;
}

bool MainView::still() const {
  return !camera_dirty_ && now_seconds() - camera_moved_at_ > kStillSeconds &&
         image_.width() == fb_w_;
}

void MainView::set_window_size(int width, int height) {
  const GuiWindow::ViewArea a = window_.view_area();
  fb_w_ = a.width;
  area_x_ = a.x;
  fb_h_ = height;
  window_w_ = width;
}

MainView::Rendered MainView::render(
    const FrameSnapshot& s, std::uint64_t generation, std::pair<int, int> teach_key, bool teaching,
    bool full, bool running, const std::function<FrameSnapshot(const FrameSnapshot&)>& drawn) {
  const int f = reduction_.now(moving(), running, full);
  const int w = std::max(1, fb_w_ / f), h = std::max(1, fb_h_ / f);
  const bool new_snapshot = generation != drawn_generation_;
  const bool new_scene = new_snapshot || options_dirty_ || (teaching && drawn_teach_ != teach_key);
  if (!new_scene && !camera_dirty_ && w == image_.width() && h == image_.height()) return {};
  window_.make_current();
  image_.resize(w, h);
  target_->resize(w, h);
  view_->set_size(w, h);
  if (options_.zoom_to_focus && new_snapshot) view_->reset_camera();  // follow the focus
  if (new_scene) {
    view_->draw(drawn(s));
    drawn_generation_ = generation;
    drawn_teach_ = teach_key;
    options_dirty_ = false;
  } else {
    view_->redraw();
  }
  camera_dirty_ = false;
  return {f, new_scene};
}

void MainView::show() const {
  glClearColor(0.11f, 0.12f, 0.15f, 1.0f);  // the columns beside the view
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  image_.show(area_x_, 0, fb_w_, fb_h_);
}

void MainView::adapt_reduction(double seconds) {
  reduction_.adapt(image_.width() < fb_w_ ? fb_w_ / std::max(1, image_.width()) : 1, seconds);
}

render::Image MainView::read_image() {
  target_->make_current();
  return target_->read_image();
}

std::array<double, 2> MainView::image_pixel(double x, double y,
                                            std::array<int, 2> window_size) const {
  // Cursor positions are in window units, the framebuffer and the image in pixels.
  const double fb_x = x * window_w_ / std::max(1, window_size[0]) - area_x_;
  return {fb_x * image_.width() / std::max(1, fb_w_),
          y * image_.height() / std::max(1, window_size[1])};
}

std::optional<Index> MainView::pick(const FrameSnapshot& s, double x, double y,
                                    std::array<int, 2> window_size) {
  if (image_.width() == 0) return std::nullopt;
  const auto [px, py] = image_pixel(x, y, window_size);
  if (px < 0.0 || px >= image_.width()) return std::nullopt;  // beside the view
  const auto [near, far] = view_->sight_line(px, py);
  const auto hit = render::first_sphere_hit(near, far, s.position, s.radius);
  if (!hit) return std::nullopt;
  return s.id[*hit];
}

}  // namespace drumlab::gui
