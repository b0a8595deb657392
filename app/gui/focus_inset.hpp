#pragma once
// The focus inset: a second view of the same snapshot framing the focus particle's search,
// rendered into its own ViewImage and shown in an ImGui window.
#include <cstdint>
#include <functional>
#include <memory>

#include "app/gui/gui_window.hpp"
#include "app/gui/view_image.hpp"
#include "render/current_gl_context.hpp"
#include "render/drum_view.hpp"

namespace drumlab::gui {

class FocusInset {
 public:
  explicit FocusInset(const GuiWindow& window, bool on) : window_(window), on_(on) {}
  ~FocusInset();
  FocusInset(const FocusInset&) = delete;
  FocusInset& operator=(const FocusInset&) = delete;

  bool on() const { return on_; }
  void set_on(bool on) { on_ = on; }
  /// The main view drew its scene anew: the inset follows.
  void mark_dirty() { dirty_ = true; }
  /// Renders the inset of `s` (as `drawn` gives it) with the main view's `options` when it is on,
  /// there is a focus with a search, and the main view drew snapshot `generation` since.
  void render(const FrameSnapshot& s, std::uint64_t generation, const render::ViewOptions& options,
              const std::function<FrameSnapshot(const FrameSnapshot&)>& drawn);
  /// Its ImGui window (bottom right), with a close box.
  void panel(std::optional<Index> focus_id);

 private:
  const GuiWindow& window_;
  bool on_ = true;
  int size_ = GuiWindow::kInsetSize;
  ViewImage image_;
  std::unique_ptr<render::CurrentGlContext> target_;
  std::unique_ptr<render::DrumView> view_;
  std::uint64_t generation_ = 0;
  bool dirty_ = true;
};

}  // namespace drumlab::gui
