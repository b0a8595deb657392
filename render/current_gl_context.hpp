#pragma once
// A RenderTarget over an OpenGL context the caller owns and has created already (a GLFW window's,
// a GLX pbuffer): no OSMesa, no GLX shim. The view draws into the context's default framebuffer
// (what is bound as framebuffer 0 when make_current() returns); read_image() reads it back with
// glReadPixels. A GUI that shows the frame as a texture (ImGui::Image) can instead bind its own
// FBO in `make_current` and keep its texture; read_image() then reads that FBO.
#include <functional>

#include "render/render_target.hpp"

namespace drumlab::render {

class CurrentGlContext final : public RenderTarget {
 public:
  /// `make_current` makes the caller's context current (e.g. glfwMakeContextCurrent(window));
  /// empty: the context is current already and stays so.
  CurrentGlContext(int width, int height, std::function<void()> make_current = {});

  int width() const override { return width_; }
  int height() const override { return height_; }
  void make_current() override;
  Image read_image() const override;
  /// Follows a resized window (the next DrumView frame must be of this size too).
  void resize(int width, int height);

 private:
  int width_ = 0;
  int height_ = 0;
  std::function<void()> make_current_;
};

}  // namespace drumlab::render
