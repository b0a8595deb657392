#pragma once
// Where the UI thread's time goes (drumlab-gui --bench).
#include <cstdint>

namespace drumlab::gui {

/// The UI thread's time summed over frames (with glFinish between the parts, so the GL work is
/// charged to the part that issued it; only while measuring).
struct FrameProfile {
  double panels = 0.0;  ///< ImGui's panels built (CPU)
  double view = 0.0;    ///< the VTK view rendered into its image (when something changed)
  double inset = 0.0;   ///< the focus inset rendered
  double show = 0.0;    ///< the view's image blitted into the window
  double imgui = 0.0;   ///< ImGui drawn over it
  double swap = 0.0;    ///< buffers swapped
  double wait = 0.0;    ///< paced: waiting for the next frame (running) or events
  std::uint64_t frames = 0;
  std::uint64_t renders = 0;  ///< frames that rendered the view (the others showed the last image)
  std::uint64_t reduction_sum = 0;  ///< the reduction factors of those renders, summed
};

}  // namespace drumlab::gui
