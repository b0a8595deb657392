// The workbench's Run and View panels (the others are their parts' own: SceneEditor,
// SearchPanel, ExportPanel, Teaching, FocusInset). Each reads the shown FrameSnapshot and calls
// public setters of the SimThread (run, step, restart) or the MainView (options, camera,
// reduction): no physics here.
#include <numbers>
#include <string>

#include <imgui.h>

#include "app/gui/gui_app.hpp"
#include "app/gui/gui_session.hpp"

namespace drumlab::gui {

void GuiApp::panel_run() {
  window_->place(GuiWindow::kMargin, GuiWindow::kMargin, GuiWindow::kLeftPanels);
  ImGui::Begin("Run");
  const FrameSnapshot* s = shown_.get();
  ImGui::TextUnformatted(sim_->state_text().c_str());
  const bool running = sim_->running();
  if (ImGui::Button(running ? "Pause" : "Run")) sim_->set_running(!running);
  ImGui::SameLine();
  if (ImGui::Button("Step")) sim_->single_step();
  ImGui::SameLine();
  if (ImGui::Button("Reset")) {
    sim_->restart(gui_scene(options_.scene));
    scene_editor_->reset();
  }
  int chunk = static_cast<int>(options_.steps_per_frame);
  if (ImGui::SliderInt("steps / frame", &chunk, 1, 500)) {
    options_.steps_per_frame = static_cast<std::uint64_t>(chunk);
    sim_->set_chunk(options_.steps_per_frame);
  }
  if (s != nullptr) {
    ImGui::Text("t = %.4f s   step %llu   N = %zu", s->time,
                static_cast<unsigned long long>(s->steps), s->size());
    ImGui::Text("revolutions %.3f   omega %.3f rad/s", s->drum_angle / (2.0 * std::numbers::pi),
                s->drum_omega);
  }
  ImGui::Text("%.1f frames/s   sim %.2f M particle-steps/s", clock_.fps,
              sim_->particle_steps_per_second() / 1e6);
  if (const std::optional<TeamChooser> t = sim_->team()) {
    ImGui::Text("threads %d, adaptive: %d now", t->threads(), t->team());
    ImGui::Text("windows on %d / 1 thread: %llu / %llu", t->threads(),
                static_cast<unsigned long long>(t->full_windows()),
                static_cast<unsigned long long>(t->single_windows()));
  } else if (options_.threads > 1) {
    ImGui::Text("threads %d (fixed team)", options_.threads);
  }
  ImGui::End();
}

void GuiApp::panel_view(const FrameSnapshot* s) {
  window_->place(GuiWindow::kMargin, -300.0f, GuiWindow::kLeftPanels);
  ImGui::Begin("View");
  render::ViewOptions o = view_->options();
  bool changed = view_switches(o, s);
  camera_buttons(o);
  ImGui::TextDisabled("drag: orbit, wheel: zoom, click: focus");
  speed_fields();
  changed |= focus_fields(o, s);
  if (changed) set_view_options(o);
  ImGui::End();
}

bool GuiApp::view_switches(render::ViewOptions& o, const FrameSnapshot* s) {
  bool changed = false;
  const std::string_view current = render::color_by_name(o.color_by);
  if (ImGui::BeginCombo("colour by", std::string(current).c_str())) {
    for (const render::ColorByName& m : render::color_by_names()) {
      if (ImGui::Selectable(std::string(m.name).c_str(), m.value == o.color_by)) {
        o.color_by = m.value;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  const bool has_grid = s != nullptr && s->grid.has_value();
  if (!has_grid) ImGui::BeginDisabled();
  changed |= ImGui::Checkbox("grid occupancy", &o.grid);
  if (!has_grid) {
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled("(no cell grid)");
    if (o.grid) {
      o.grid = false;
      changed = true;
    }
  }
  changed |= ImGui::Checkbox("walls", &o.walls);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("legend", &o.legend);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("text", &o.text);
  changed |= ImGui::Checkbox("grey particles (the focus colours stand out)", &o.neutral_particles);
  if (s != nullptr && s->orbit_radius != 0.0) {  // a planetary drum: the frame of the picture
    int frame = static_cast<int>(o.frame);
    ImGui::TextUnformatted("frame");
    ImGui::SameLine();
    changed |= ImGui::RadioButton("drum", &frame, static_cast<int>(paraview::ViewFrame::drum));
    ImGui::SameLine();
    changed |= ImGui::RadioButton("arm (field down)", &frame,
                                  static_cast<int>(paraview::ViewFrame::carrier));
    ImGui::SameLine();
    changed |= ImGui::RadioButton("lab", &frame, static_cast<int>(paraview::ViewFrame::lab));
    o.frame = static_cast<paraview::ViewFrame>(frame);
  }
  return changed;
}

void GuiApp::camera_buttons(render::ViewOptions& o) {
  if (ImGui::Button("camera: axis")) {
    o.camera = render::CameraMode::axis;
    view_->set_camera_mode(o.camera);
  }
  ImGui::SameLine();
  if (ImGui::Button("camera: iso")) {
    o.camera = render::CameraMode::iso;
    view_->set_camera_mode(o.camera);
  }
}

void GuiApp::speed_fields() {
  if (!ImGui::TreeNode("speed")) return;  // ParaView's image reduction while interacting
  ImageReduction r = view_->reduction();
  bool changed = ImGui::Checkbox("reduce while moving: auto (30 frames/s)", &r.automatic);
  if (!r.automatic) changed |= ImGui::SliderInt("reduction factor", &r.factor, 1, 4);
  changed |= ImGui::Checkbox("the view moves while the simulation runs", &r.while_running);
  if (changed) view_->set_reduction(r);
  ImGui::SliderFloat("frames/s at most while running", &clock_.max_running_fps, 2.0f, 60.0f,
                     "%.0f");
  ImGui::TreePop();
}

bool GuiApp::focus_fields(render::ViewOptions& o, const FrameSnapshot* s) {
  bool changed = false;
  int id = o.focus_id ? static_cast<int>(*o.focus_id) : -1;
  if (ImGui::InputInt("focus id", &id) && s != nullptr) {
    if (id >= 0 && static_cast<std::size_t>(id) < s->size()) {
      o.focus_id = static_cast<Index>(id);
    } else {
      o.focus_id.reset();
    }
    teaching_.show_whole_search();
    changed = true;
  }
  if (ImGui::Button("auto focus") && s != nullptr) {
    Particles p;  // auto_focus_id reads positions and radii only
    p.position = s->position;
    p.radius = s->radius;
    p.id = s->id;
    o.focus_id = render::auto_focus_id(p);
    changed = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("no focus")) {
    o.focus_id.reset();
    o.zoom_to_focus = false;
    changed = true;
  }
  bool inset = inset_->on();
  if (ImGui::Checkbox("inset", &inset)) inset_->set_on(inset);
  ImGui::SameLine();
  if (ImGui::Checkbox("zoom to focus", &o.zoom_to_focus)) {
    changed = true;
    if (!o.zoom_to_focus) view_->camera_changed(true);
  }
  if (o.focus_id && s != nullptr && s->focus_visit) {
    const SearchVisit& v = *s->focus_visit;
    const auto id = static_cast<unsigned>(*o.focus_id);
    if (v.kind == SearchVisit::Kind::list) {
      ImGui::Text("focus %u: listed partners %zu, contacts %zu", id, v.candidates.size(),
                  v.contacts.size());
    } else {
      ImGui::Text("focus %u: cells %zu, tested %zu, contacts %zu", id, v.cells_visited,
                  v.pairs_tested, v.contacts.size());
    }
  }
  return changed;
}

}  // namespace drumlab::gui
