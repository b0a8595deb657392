#include "render/current_gl_context.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <GL/gl.h>

namespace drumlab::render {

CurrentGlContext::CurrentGlContext(int width, int height, std::function<void()> make_current)
    : make_current_(std::move(make_current)) {
  resize(width, height);
}

void CurrentGlContext::resize(int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::runtime_error("GL context target: size must be positive, got " +
                             std::to_string(width) + "x" + std::to_string(height));
  }
  width_ = width;
  height_ = height;
}

void CurrentGlContext::make_current() {
  if (make_current_) make_current_();
}

Image CurrentGlContext::read_image() const {
  glFinish();
  Image img;
  img.width = width_;
  img.height = height_;
  img.rgb.resize(3 * static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
  std::vector<std::uint8_t> rows(img.rgb.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  const std::size_t row = 3 * static_cast<std::size_t>(width_);
  for (int y = 0; y < height_; ++y) {  // OpenGL's rows run bottom to top
    std::copy_n(rows.data() + row * static_cast<std::size_t>(height_ - 1 - y), row,
                img.rgb.data() + row * static_cast<std::size_t>(y));
  }
  return img;
}

}  // namespace drumlab::render
