#pragma once
// An OSMesa (software OpenGL) context rendering into our own RGBA buffer: VTK draws into it with no
// X server and no DISPLAY. The executable must also link app/cli/osmesa_glx_shim.cpp (see
// render/README.md, section "Rendering without a display").
#include <array>
#include <cstdint>
#include <vector>

namespace drumlab::render {

/// An RGB image, rows top to bottom.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 bytes per pixel

  std::array<std::uint8_t, 3> pixel(int x, int y) const {
    const std::size_t k = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(x));
    return {rgb[k], rgb[k + 1], rgb[k + 2]};
  }
};

/// Owns an OSMesa core-profile context (3.2+) and its colour buffer; current after construction.
/// Throws std::runtime_error if OSMesa cannot create or bind the context.
class OffscreenContext {
 public:
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  void make_current();
  int width() const { return width_; }
  int height() const { return height_; }
  /// Waits for OpenGL to finish and copies the buffer (flipped to top-down rows).
  Image read_image() const;

 private:
  void* context_ = nullptr;  // OSMesaContext
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> buffer_;  // RGBA, bottom row first
};

}  // namespace drumlab::render
