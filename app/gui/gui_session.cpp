#include "app/gui/gui_session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>

namespace drumlab::gui {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

SessionOptions session_options(const GuiOptions& o) {
  SessionOptions s;
  s.scene_file = o.scene;
  s.method = o.method;
  s.settle_time = o.settle_time;
  s.adaptive_team = o.team == "adaptive";
  return s;
}

SceneConfig gui_scene(const std::string& file) {
  return with_gui_checks(load_dynamic_scene(file));
}

SceneConfig with_gui_checks(SceneConfig scene) {
  scene.output.diagnostics_every = std::min<std::uint64_t>(scene.output.diagnostics_every, 50);
  return scene;
}

}  // namespace drumlab::gui
