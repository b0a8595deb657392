#include "render/offscreen_context.hpp"

#include <stdexcept>
#include <string>

#include <GL/osmesa.h>

namespace drumlab::render {

OffscreenContext::OffscreenContext(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0) {
    throw std::runtime_error("offscreen context: size must be positive, got " +
                             std::to_string(width) + "x" + std::to_string(height));
  }
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         24,
                         OSMESA_STENCIL_BITS,
                         8,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         2,
                         0};
  context_ = OSMesaCreateContextAttribs(attribs, nullptr);
  if (context_ == nullptr) {
    throw std::runtime_error("offscreen context: OSMesa could not create a 3.2 core context");
  }
  buffer_.assign(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  make_current();
}

OffscreenContext::~OffscreenContext() {
  if (context_ != nullptr) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void OffscreenContext::make_current() {
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), buffer_.data(), GL_UNSIGNED_BYTE,
                         width_, height_)) {
    throw std::runtime_error("offscreen context: OSMesaMakeCurrent failed");
  }
}

Image OffscreenContext::read_image() const {
  glFinish();
  Image img;
  img.width = width_;
  img.height = height_;
  img.rgb.resize(3 * static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
  for (int y = 0; y < height_; ++y) {
    const std::uint8_t* src = buffer_.data() + 4 * static_cast<std::size_t>(height_ - 1 - y) *
                                                   static_cast<std::size_t>(width_);
    std::uint8_t* dst = img.rgb.data() + 3 * static_cast<std::size_t>(y) * width_;
    for (int x = 0; x < width_; ++x) {
      dst[3 * x] = src[4 * x];
      dst[3 * x + 1] = src[4 * x + 1];
      dst[3 * x + 2] = src[4 * x + 2];
    }
  }
  return img;
}

}  // namespace drumlab::render
