#include "app/gui/gui_window.hpp"

#include <algorithm>
#include <stdexcept>

#include <imgui.h>
#include <imgui_internal.h>  // the frame's windows, for panels_shown()
// clang-format off
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <GLFW/glfw3.h>
// clang-format on

namespace drumlab::gui {

GuiWindow::GuiWindow(int width, int height, bool vsync) {
  if (glfwInit() != GLFW_TRUE) {
    throw std::runtime_error("no display for the window (set DISPLAY, or run under xvfb-run)");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 2);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, "drumlab-gui", nullptr, nullptr);
  if (window_ == nullptr) {
    glfwTerminate();
    throw std::runtime_error("could not open an OpenGL 3.2 core window");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(vsync ? 1 : 0);
  glfwGetFramebufferSize(window_, &fb_w_, &fb_h_);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout is the program's, not a file's
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 150");
}

GuiWindow::~GuiWindow() {
  glfwMakeContextCurrent(window_);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void GuiWindow::make_current() const {
  glfwMakeContextCurrent(window_);
}

std::array<int, 2> GuiWindow::window_size() const {
  std::array<int, 2> s{0, 0};
  glfwGetWindowSize(window_, &s[0], &s[1]);
  return s;
}

bool GuiWindow::should_close() const {
  return glfwWindowShouldClose(window_) != 0;
}

void GuiWindow::begin_frame() const {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

bool GuiWindow::track_size() {
  relayout_ = false;
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  if (w > 0 && h > 0 && (w != fb_w_ || h != fb_h_)) {  // the window was resized
    fb_w_ = w;
    fb_h_ = h;
    relayout_ = true;
  }
  return relayout_;
}

void GuiWindow::place(float x, float y, float w, float h) const {
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  const ImGuiCond when = relayout_ ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(ImVec2(x < 0.0f ? size.x + x : x, y < 0.0f ? size.y + y : y), when);
  ImGui::SetNextWindowSize(ImVec2(w, h), when);
}

std::vector<GuiWindow::PanelRect> GuiWindow::panels_shown() {
  std::vector<PanelRect> out;
  for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows) {
    if (!w->Active || w->Hidden || (w->Flags & ImGuiWindowFlags_ChildWindow) != 0) continue;
    if ((w->Flags & (ImGuiWindowFlags_Tooltip | ImGuiWindowFlags_Popup)) != 0) continue;
    const std::string name(w->Name);
    if (name.starts_with("Debug##")) continue;  // ImGui's implicit window
    out.push_back({name.substr(0, name.find("##")), w->Pos.x, w->Pos.y, w->Size.x, w->Size.y});
  }
  return out;
}

GuiWindow::ViewArea GuiWindow::view_area() const {
  const std::array<int, 2> units = window_size();
  const double scale = static_cast<double>(fb_w_) / std::max(1, units[0]);  // pixels per unit
  const double free = units[0] - kLeftColumn - kRightColumn;
  if (free < kMinViewWidth) return {0, fb_w_};
  return {static_cast<int>(kLeftColumn * scale), static_cast<int>(free * scale)};
}

}  // namespace drumlab::gui
