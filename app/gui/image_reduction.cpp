#include "app/gui/image_reduction.hpp"

#include <algorithm>

namespace drumlab::gui {

namespace {

/// The frame rate a moving view aims at, and the largest reduction it may use.
constexpr double kInteractiveFps = 30.0;
constexpr int kMaxReduction = 4;

}  // namespace

int ImageReduction::now(bool moving, bool running, bool full) const {
  if (full || !(moving || (while_running && running))) return 1;
  return automatic ? adaptive : std::max(1, factor);
}

void ImageReduction::adapt(int used, double seconds) {
  // VTK's desired update rate for interaction: the factor that keeps a moving frame within
  // 1 / kInteractiveFps s (pixels scale as 1 / factor^2).
  if (used == 1 || !automatic) return;
  const double budget = 1.0 / kInteractiveFps;
  if (seconds > budget && adaptive < kMaxReduction) ++adaptive;
  if (seconds < 0.3 * budget && adaptive > 2) --adaptive;
}

}  // namespace drumlab::gui
