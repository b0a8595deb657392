#include "app/gui/focus_inset.hpp"

#include <cstdint>

#include <imgui.h>

#include "app/gui/gui_window.hpp"

namespace drumlab::gui {

FocusInset::~FocusInset() {
  view_.reset();
  window_.make_current();
  image_.release();
}

void FocusInset::render(const FrameSnapshot& s, std::uint64_t generation,
                        const render::ViewOptions& options,
                        const std::function<FrameSnapshot(const FrameSnapshot&)>& drawn) {
  if (!on_ || !options.focus_id || !s.focus_visit) return;
  if (!dirty_ && generation_ == generation) return;
  window_.make_current();
  if (!view_) {
    image_.resize(size_, size_);
    target_ = std::make_unique<render::CurrentGlContext>(size_, size_, [this] {
      window_.make_current();
      image_.bind();
    });
    render::ViewOptions o = options;
    o.width = o.height = size_;
    o.overlay = false;  // the main view has the legend
    view_ = std::make_unique<render::DrumView>(o, *target_);
  }
  render::ViewOptions o = options;
  o.zoom_to_focus = true;
  o.overlay = false;
  o.walls = false;
  view_->set_options(o);
  view_->reset_camera();  // follow the focus particle
  view_->draw(drawn(s));
  generation_ = generation;
  dirty_ = false;
}

void FocusInset::panel(std::optional<Index> focus_id) {
  if (!view_ || !on_ || !focus_id) return;
  window_.place(GuiWindow::kRightX, GuiWindow::kInsetY, 0);  // right column, above Export
  ImGui::Begin("Focus inset", &on_, ImGuiWindowFlags_AlwaysAutoResize);
  const auto size = static_cast<float>(size_);
  // The texture's rows run bottom to top: flip it.
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(image_.texture())),
               ImVec2(size, size), ImVec2(0, 1), ImVec2(1, 0));
  ImGui::TextDisabled("focus %u, its search framed", static_cast<unsigned>(*focus_id));
  ImGui::End();
}

}  // namespace drumlab::gui
