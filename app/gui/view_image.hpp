#pragma once
// The picture the VTK view renders into: a framebuffer object with one colour texture, in the
// window's own GL context. The window shows it by a scaled blit (so the view can be rendered at a
// reduced size while the camera moves, ParaView's "image reduction factor", and shown again
// without rendering while nothing changed), an inset shows it with ImGui::Image.
#include <cstdint>

namespace drumlab::gui {

class ViewImage {
 public:
  ViewImage() = default;
  ~ViewImage();
  /// Deletes its GL objects (the context current); the destructor does too, if not released.
  void release();
  ViewImage(const ViewImage&) = delete;
  ViewImage& operator=(const ViewImage&) = delete;

  /// (Re)allocates the texture for width x height pixels if the size changed (context current).
  void resize(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  /// Binds it as the framebuffer to draw into and read from (render::CurrentGlContext's
  /// make_current does, so the view renders into it and read_image() reads it).
  void bind() const;
  /// Binds the window's own (default) framebuffer.
  static void bind_window();
  /// Draws it into the rectangle of the window's default framebuffer from pixel (x, y) (from the
  /// bottom left), w x h pixels, scaled with linear filtering.
  void show(int x, int y, int width, int height) const;
  /// The colour texture (for ImGui::Image).
  std::uint32_t texture() const { return texture_; }

 private:
  std::uint32_t framebuffer_ = 0;
  std::uint32_t texture_ = 0;
  std::uint32_t depth_ = 0;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace drumlab::gui
