#pragma once
// ParaView's image reduction while interacting: the view is rendered at 1 / factor of the window's
// size while it moves (the camera, or the particles while the simulation runs), adapted to keep a
// moving frame within 1 / 30 s, and at full size once still.
namespace drumlab::gui {

struct ImageReduction {
  int factor = 2;             ///< the factor while the view moves (1: none), when not automatic
  bool automatic = true;      ///< adapt the factor to 30 frames/s instead (2..4)
  bool while_running = true;  ///< the view counts as moving while the simulation runs
  int adaptive = 2;           ///< the automatic factor now

  /// The factor for a frame (1: full size).
  int now(bool moving, bool running, bool full) const;
  /// Adapts the automatic factor to the time a frame reduced by `used` took.
  void adapt(int used, double seconds);
};

}  // namespace drumlab::gui
