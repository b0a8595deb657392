#include "app/gui/gui_window.hpp"

#include <stdexcept>

#include <imgui.h>
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

void GuiWindow::place(float x, float y, float w) const {
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  const ImGuiCond when = relayout_ ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(ImVec2(x < 0.0f ? size.x + x : x, y < 0.0f ? size.y + y : y), when);
  ImGui::SetNextWindowSize(ImVec2(w, 0.0f), when);
}

}  // namespace drumlab::gui
