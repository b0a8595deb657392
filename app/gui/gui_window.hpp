#pragma once
// The workbench's window: GLFW (a real GLX context, OpenGL 3.2 core) and Dear ImGui with its GLFW
// and OpenGL3 backends; its framebuffer size, and where the panels go in it.
#include <array>

struct GLFWwindow;

namespace drumlab::gui {

class GuiWindow {
 public:
  /// Opens a width x height window; `vsync`: swap with the display's refresh. Throws
  /// std::runtime_error without a display.
  GuiWindow(int width, int height, bool vsync);
  ~GuiWindow();
  GuiWindow(const GuiWindow&) = delete;
  GuiWindow& operator=(const GuiWindow&) = delete;

  GLFWwindow* glfw() const { return window_; }
  /// Makes the window's GL context current.
  void make_current() const;
  /// The framebuffer's size in pixels.
  int width() const { return fb_w_; }
  int height() const { return fb_h_; }
  /// The window's size in window units (cursor positions).
  std::array<int, 2> window_size() const;
  bool should_close() const;

  /// Starts ImGui's frame.
  void begin_frame() const;
  /// After the panels of a frame: reads the framebuffer size; true if it changed (the next
  /// frame's panels are placed again).
  bool track_size();
  /// Places the next ImGui window at (x, y), w wide (x, y < 0: from the right / bottom edge);
  /// again whenever the window changed size.
  void place(float x, float y, float w) const;

 private:
  GLFWwindow* window_ = nullptr;
  int fb_w_ = 0, fb_h_ = 0;
  bool relayout_ = false;  ///< the window changed size: place the panels again
};

}  // namespace drumlab::gui
