#pragma once
// An OSMesa (software OpenGL) context rendering into our own RGBA buffer: VTK draws into it with no
// X server and no DISPLAY. Library drumlab_render_osmesa; the executable must also link
// app/cli/osmesa_glx_shim.cpp (see render/README.md, section "Rendering without a display").
#include <cstdint>
#include <vector>

#include "render/image.hpp"
#include "render/render_target.hpp"

namespace drumlab::render {

/// Owns an OSMesa core-profile context (3.2+) and its colour buffer; current after construction.
/// Throws std::runtime_error if OSMesa cannot create or bind the context.
class OffscreenContext final : public RenderTarget {
 public:
  OffscreenContext(int width, int height);
  ~OffscreenContext() override;
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  void make_current() override;
  int width() const override { return width_; }
  int height() const override { return height_; }
  /// Waits for OpenGL to finish and copies the buffer (flipped to top-down rows).
  Image read_image() const override;

 private:
  void* context_ = nullptr;  // OSMesaContext
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> buffer_;  // RGBA, bottom row first
};

}  // namespace drumlab::render
