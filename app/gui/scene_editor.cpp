#include "app/gui/scene_editor.hpp"

#include <algorithm>
#include <numbers>

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "app/gui/gui_options.hpp"
#include "app/gui/gui_session.hpp"
#include "app/gui/gui_window.hpp"
#include "engine/scene/scene_validation.hpp"
#include "engine/scene/scene_writer.hpp"

namespace drumlab::gui {

namespace {

bool input_double(const char* label, double& v, double step, const char* format) {
  return ImGui::InputDouble(label, &v, step, 10.0 * step, format);
}

}  // namespace

SceneEditor::SceneEditor(std::string file, const std::vector<std::string>& edits)
    : file_(std::move(file)), edited_(load_dynamic_scene(file_)) {
  for (const std::string& e : edits) apply_edit(edited_, e);
}

void SceneEditor::reset() {
  edited_ = load_dynamic_scene(file_);
}

void SceneEditor::save(const std::string& file) const {
  save_scene(edited_, file);
}

void SceneEditor::panel(const GuiWindow& window, SimThread& sim) {
  window.place(GuiWindow::kMargin, 190, GuiWindow::kLeftPanels);
  ImGui::Begin("Scene", nullptr, ImGuiWindowFlags_None);
  ImGui::TextWrapped("%s", edited_.name.c_str());
  double rpm = edited_.drum.omega * 60.0 / (2.0 * std::numbers::pi);
  input_double("omega (rad/s)", edited_.drum.omega, 0.1, "%.3f");
  if (input_double("rpm", rpm, 1.0, "%.2f")) {
    edited_.drum.omega = rpm * 2.0 * std::numbers::pi / 60.0;
  }
  input_double("friction", edited_.material.friction, 0.05, "%.3f");
  input_double("restitution", edited_.material.restitution, 0.05, "%.3f");
  input_double("wall friction", edited_.wall.friction, 0.05, "%.3f");
  class_fields();
  fill_fields();
  mesh_lines();
  if (ImGui::Button("Restart from edited scene")) {
    if (const auto problem = scene_problem(edited_)) {  // the loader's ranges, not a crash
      message_ = fmt::format("not restarted: {}: {}", problem->key, problem->reason);
    } else {
      sim.restart(with_gui_checks(edited_));
      message_ = "restarted (paused): press Run";
    }
  }
  ImGui::InputText("##scenefile", &save_path_);
  ImGui::SameLine();
  if (ImGui::Button("Save scene as TOML")) {
    try {
      save(save_path_);
      message_ = fmt::format("wrote {}", save_path_);
    } catch (const std::exception& e) {
      message_ = e.what();
    }
  }
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
  ImGui::End();
}

void SceneEditor::class_fields() {
  if (!ImGui::TreeNode("particle classes")) return;
  for (std::size_t k = 0; k < edited_.classes.size(); ++k) {
    ParticleClass& c = edited_.classes[k];
    ImGui::PushID(static_cast<int>(k));
    ImGui::Text("%s (%s)", c.name.c_str(), size_kind_name(c.distribution).data());
    if (c.distribution == SizeKind::table) {
      ImGui::Text("%zu radii, %.3f to %.3f mm", c.radii.size(), 1000.0 * c.min_radius(),
                  1000.0 * c.max_radius());
    } else {
      double mm = 1000.0 * c.radius;
      const bool spread = c.polydisperse();
      if (input_double(spread ? "mean radius (mm)" : "radius (mm)", mm, 0.5, "%.3f")) {
        c.radius = mm / 1000.0;
      }
      double sigma_mm = 1000.0 * c.radius_sigma;
      if (spread && input_double("radius sigma (mm)", sigma_mm, 0.05, "%.4f")) {
        c.radius_sigma = sigma_mm / 1000.0;
      }
    }
    input_double("volume share", c.volume_fraction, 0.05, "%.4f");
    ImGui::PopID();
  }
  ImGui::TreePop();
}

void SceneEditor::mesh_lines() const {
  if (!edited_.has_meshes() || !ImGui::TreeNode("triangle walls")) return;
  for (std::size_t k = 0; k < edited_.meshes.size(); ++k) {
    const MeshWallConfig& m = edited_.meshes[k];
    ImGui::TextWrapped("wall.mesh[%zu]: %s, %s", k, m.file.filename().string().c_str(),
                       m.attach == MeshAttach::drum ? "turning with the drum" : "fixed in the lab");
  }
  for (std::size_t k = 0; k < edited_.lifters.size(); ++k) {
    const LifterWallConfig& l = edited_.lifters[k];
    ImGui::TextWrapped("wall.lifters[%zu]: %d %s, %.1f mm high", k, l.count,
                       l.shape == LifterKind::angled ? "angled" : "straight", 1000.0 * l.height);
  }
  ImGui::TextWrapped(
      "as the scene file sets them, with their own material (wall friction above: "
      "the drum's)");
  ImGui::TreePop();
}

void SceneEditor::fill_fields() {
  int count = static_cast<int>(edited_.fill.count);
  if (ImGui::InputInt("particles (fill)", &count, 100, 1000)) {
    edited_.fill.count = static_cast<std::size_t>(std::max(0, count));
  }
  input_double("fill fraction", edited_.fill.volume_fraction, 0.01, "%.3f");
  int seed = static_cast<int>(edited_.fill.seed);
  if (ImGui::InputInt("fill seed", &seed)) edited_.fill.seed = static_cast<std::uint64_t>(seed);
  input_double("settle time (s)", edited_.fill.settle_time, 0.05, "%.3f");
}

}  // namespace drumlab::gui
