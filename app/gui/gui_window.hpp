#pragma once
// The workbench's window: GLFW (a real GLX context, OpenGL 3.2 core) and Dear ImGui with its GLFW
// and OpenGL3 backends; its framebuffer size, and where the panels go in it.
#include <array>
#include <string>
#include <vector>

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
  /// Places the next ImGui window at (x, y), w wide and h high (0: fitted to its content; x, y <
  /// 0: from the right / bottom edge); again whenever the window changed size.
  void place(float x, float y, float w, float h = 0.0f) const;

  /// The layout: panels in two side columns (Run, Scene, View, Teaching on the left; Search,
  /// Focus inset, Export on the right), the view in the rest. Widths in window units; a column is
  /// its panels' width and a margin on either side.
  static constexpr float kMargin = 10.0f;
  static constexpr float kLeftPanels = 330.0f;
  static constexpr float kRightPanels = 360.0f;
  static constexpr float kLeftColumn = kLeftPanels + 2.0f * kMargin;
  static constexpr float kRightColumn = kRightPanels + 2.0f * kMargin;
  /// Narrowest view (window units) for which the columns are kept free; a narrower window lays
  /// the view under the panels.
  static constexpr float kMinViewWidth = 320.0f;
  /// x of the right column's panels (from the right edge).
  static constexpr float kRightX = -(kRightPanels + kMargin);
  /// The right column's lower panels, from the bottom edge: Export, and above it the Focus inset
  /// (kInsetSize pixels square); the Search panel fills the rest and scrolls.
  static constexpr float kExportY = -130.0f;
  static constexpr int kInsetSize = 330;
  static constexpr float kInsetY = kExportY - kInsetSize - 80.0f;
  /// The left column's Teaching panel (between Scene and View).
  static constexpr float kTeachingY = -340.0f;

  /// The view's part of the framebuffer: pixels [x, x + width) of every row.
  struct ViewArea {
    int x = 0;
    int width = 0;
  };
  ViewArea view_area() const;

  /// A panel drawn in the last frame: its title and rectangle (window units, from the top left).
  struct PanelRect {
    std::string name;
    float x = 0.0f, y = 0.0f, width = 0.0f, height = 0.0f;
  };
  /// The panels of the frame just ended (collapsed ones as their title bar).
  static std::vector<PanelRect> panels_shown();

 private:
  GLFWwindow* window_ = nullptr;
  int fb_w_ = 0, fb_h_ = 0;
  bool relayout_ = false;  ///< the window changed size: place the panels again
};

}  // namespace drumlab::gui
