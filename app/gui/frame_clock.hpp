#pragma once
// The frame rate: the cap while the simulation runs, when the last frame began, and the frames
// per second the Run panel shows.
#include <cstdint>

namespace drumlab::gui {

struct FrameClock {
  float max_running_fps = 15;   ///< frames/s at most while the simulation runs
  double last_frame = 0.0;      ///< s (now_seconds) when the last frame began
  double fps = 0.0;             ///< over the last half second or more
  double counting_since = 0.0;  ///< s
  std::uint64_t counted = 0;    ///< frames since counting_since

  void start(double t) { last_frame = counting_since = t; }
  /// A frame begins at `t`.
  void tick(double t) {
    ++counted;
    if (t - counting_since >= 0.5) {
      fps = static_cast<double>(counted) / (t - counting_since);
      counting_since = t;
      counted = 0;
    }
    last_frame = t;
  }
};

}  // namespace drumlab::gui
