#pragma once
// An RGB image, the product of every renderer here (frames, charts, the teaching figure).
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

}  // namespace drumlab::render
