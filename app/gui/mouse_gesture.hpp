#pragma once
// The left mouse button over the view: a press that moves more than a few pixels is a drag (the
// camera orbits by the moves), one that does not is a click (a pick).
#include <array>
#include <cmath>
#include <optional>

namespace drumlab::gui {

class MouseGesture {
 public:
  void press(double x, double y) {
    dragging_ = false;
    press_x_ = last_x_ = x;
    press_y_ = last_y_ = y;
  }
  /// The button held at (x, y): the move since the last call once it is a drag.
  std::optional<std::array<double, 2>> hold(double x, double y) {
    if (std::hypot(x - press_x_, y - press_y_) > 4.0) dragging_ = true;
    std::optional<std::array<double, 2>> move;
    if (dragging_ && (x != last_x_ || y != last_y_)) move = std::array{x - last_x_, y - last_y_};
    last_x_ = x;
    last_y_ = y;
    return move;
  }
  /// The button released: true for a click (no drag).
  bool release() {
    const bool click = !dragging_;
    dragging_ = false;
    return click;
  }
  bool dragging() const { return dragging_; }

 private:
  bool dragging_ = false;
  double press_x_ = 0.0, press_y_ = 0.0, last_x_ = 0.0, last_y_ = 0.0;
};

}  // namespace drumlab::gui
