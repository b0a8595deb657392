// The workbench's panels. Each reads the shown FrameSnapshot and calls public setters of the
// SimThread (run, step, method, restart, what the snapshot holds) or the DrumView (options,
// camera): no physics here.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "app/gui/gui_app.hpp"
#include "render/movie_writer.hpp"
#include "render/vtu_series_writer.hpp"

namespace drumlab::gui {

namespace {

void plot(const char* label, const History& h, const char* unit) {
  if (h.values.empty()) return;
  std::vector<float> v(h.values.begin(), h.values.end());
  const std::string overlay = fmt::format("{:.3g} {}", v.back(), unit);
  ImGui::PlotLines(label, v.data(), static_cast<int>(v.size()), 0, overlay.c_str(), FLT_MAX,
                   FLT_MAX, ImVec2(0, 50));
}

bool input_double(const char* label, double& v, double step, const char* format) {
  return ImGui::InputDouble(label, &v, step, 10.0 * step, format);
}

}  // namespace

void GuiApp::place(float x, float y, float w) const {
  // x, y < 0: from the right / bottom edge. Placed again whenever the window changed size.
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  const ImGuiCond when = relayout_ ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(ImVec2(x < 0.0f ? size.x + x : x, y < 0.0f ? size.y + y : y), when);
  ImGui::SetNextWindowSize(ImVec2(w, 0.0f), when);
}

void GuiApp::panel_run() {
  place(10, 10, 330);
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
    edited_ = load_dynamic_scene(options_.scene);
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
  ImGui::Text("%.1f frames/s   sim %.2f M particle-steps/s", fps_,
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

void GuiApp::panel_scene() {
  place(10, 190, 330);
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
  if (ImGui::TreeNode("particle classes")) {
    for (std::size_t k = 0; k < edited_.classes.size(); ++k) {
      ParticleClass& c = edited_.classes[k];
      ImGui::PushID(static_cast<int>(k));
      double mm = 1000.0 * c.radius;
      ImGui::Text("%s", c.name.c_str());
      if (input_double("radius (mm)", mm, 0.5, "%.3f")) c.radius = mm / 1000.0;
      input_double("volume share", c.volume_fraction, 0.05, "%.4f");
      ImGui::PopID();
    }
    ImGui::TreePop();
  }
  int count = static_cast<int>(edited_.fill.count);
  if (ImGui::InputInt("particles (fill)", &count, 100, 1000)) {
    edited_.fill.count = static_cast<std::size_t>(std::max(0, count));
  }
  input_double("fill fraction", edited_.fill.volume_fraction, 0.01, "%.3f");
  int seed = static_cast<int>(edited_.fill.seed);
  if (ImGui::InputInt("fill seed", &seed)) edited_.fill.seed = static_cast<std::uint64_t>(seed);
  input_double("settle time (s)", edited_.fill.settle_time, 0.05, "%.3f");
  if (ImGui::Button("Restart from edited scene")) {
    sim_->restart(with_gui_checks(edited_));
    scene_message_ = "restarted (paused): press Run";
  }
  ImGui::InputText("##scenefile", &scene_path_);
  ImGui::SameLine();
  if (ImGui::Button("Save scene as TOML")) {
    try {
      save_edited_scene(scene_path_);
      scene_message_ = fmt::format("wrote {}", scene_path_);
    } catch (const std::exception& e) {
      scene_message_ = e.what();
    }
  }
  if (!scene_message_.empty()) ImGui::TextWrapped("%s", scene_message_.c_str());
  ImGui::End();
}

void GuiApp::panel_search(const FrameSnapshot* s) {
  place(-370.0f, 10, 360);
  ImGui::Begin("Search");
  std::vector<const char*> names;
  for (const std::string& m : methods_) names.push_back(m.c_str());
  if (ImGui::Combo("method", &method_index_, names.data(), static_cast<int>(names.size()))) {
    sim_->switch_method(methods_[static_cast<std::size_t>(method_index_)]);
  }
  if (s == nullptr) {
    ImGui::End();
    return;
  }
  ImGui::TextWrapped("active: %s", s->search_name.c_str());
  const double n = std::max<double>(1.0, static_cast<double>(s->size()));
  ImGui::Text("last step: cells %llu (%.1f / particle)",
              static_cast<unsigned long long>(s->counters.cells_visited),
              static_cast<double>(s->counters.cells_visited) / n);
  ImGui::Text("pairs tested %llu (%.1f / particle)",
              static_cast<unsigned long long>(s->counters.pairs_tested),
              static_cast<double>(s->counters.pairs_tested) / n);
  ImGui::Text("pairs found %llu", static_cast<unsigned long long>(s->counters.pairs_found));
  if (ImGui::BeginTable("classes", 5, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
    for (const char* h : {"class", "N", "cells/p", "tests/p", "contacts/p"}) {
      ImGui::TableSetupColumn(h);
    }
    ImGui::TableHeadersRow();
    for (const ClassCounters& c : s->per_class) {
      const double k = std::max<double>(1.0, static_cast<double>(c.particles));
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%s %.3g mm", c.name.c_str(), 1000.0 * c.radius);
      ImGui::TableNextColumn();
      ImGui::Text("%zu", c.particles);
      ImGui::TableNextColumn();
      ImGui::Text("%.1f", static_cast<double>(c.cells_visited) / k);
      ImGui::TableNextColumn();
      ImGui::Text("%.1f", static_cast<double>(c.pairs_tested) / k);
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", static_cast<double>(c.contacts) / k);
    }
    ImGui::EndTable();
  }
  const double total = std::max(1e-12, recent_split_.total());
  ImGui::Text("step time: search %.0f%%  forces %.0f%%", 100.0 * recent_split_.search / total,
              100.0 * recent_split_.forces / total);
  ImGui::Text("           walls %.0f%%  integration %.0f%%", 100.0 * recent_split_.walls / total,
              100.0 * (recent_split_.integration + recent_split_.reorder) / total);
  plot("cells/p", cells_per_particle_, "");
  plot("tests/p", tests_per_particle_, "");
  plot("found/p", contacts_per_particle_, "");
  plot("ms/step", step_ms_, "ms");
  if (s->diagnostics) {
    const Diagnostics& d = *s->diagnostics;
    ImGui::Text("kinetic %.4g J  rotational %.4g J", d.kinetic_energy, d.rotational_energy);
    ImGui::Text("potential %.4g J  elastic %.4g J", d.potential_energy, d.elastic_energy);
    ImGui::Text("max overlap %.3f r  outside %zu", d.max_overlap_ratio, d.outside_drum);
    plot("kinetic", kinetic_, "J");
  }
  ImGui::End();
}

void GuiApp::panel_view(const FrameSnapshot* s) {
  place(10, -300.0f, 330);
  ImGui::Begin("View");
  bool changed = false;
  const auto modes = render::color_by_names();
  const std::string_view current = render::color_by_name(view_options_.color_by);
  if (ImGui::BeginCombo("colour by", std::string(current).c_str())) {
    for (const render::ColorByName& m : modes) {
      const bool selected = m.value == view_options_.color_by;
      if (ImGui::Selectable(std::string(m.name).c_str(), selected)) {
        view_options_.color_by = m.value;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  const bool has_grid = s != nullptr && s->grid.has_value();
  if (!has_grid) ImGui::BeginDisabled();
  changed |= ImGui::Checkbox("grid occupancy", &view_options_.grid);
  if (!has_grid) {
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextDisabled("(no cell grid)");
    if (view_options_.grid) {
      view_options_.grid = false;
      changed = true;
    }
  }
  changed |= ImGui::Checkbox("walls", &view_options_.walls);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("legend", &view_options_.legend);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("text", &view_options_.text);
  changed |= ImGui::Checkbox("grey particles (the focus colours stand out)",
                             &view_options_.neutral_particles);
  if (ImGui::Button("camera: axis")) {
    view_options_.camera = render::CameraMode::axis;
    view_->set_options(view_options_);
    camera_changed(true);
  }
  ImGui::SameLine();
  if (ImGui::Button("camera: iso")) {
    view_options_.camera = render::CameraMode::iso;
    view_->set_options(view_options_);
    camera_changed(true);
  }
  ImGui::TextDisabled("drag: orbit, wheel: zoom, click: focus");
  if (ImGui::TreeNode("speed")) {  // ParaView's image reduction while interacting
    ImGui::Checkbox("reduce while moving: auto (30 frames/s)", &auto_reduction_);
    if (!auto_reduction_) ImGui::SliderInt("reduction factor", &reduction_, 1, 4);
    ImGui::Checkbox("the view moves while the simulation runs", &reduce_running_);
    ImGui::SliderFloat("frames/s at most while running", &max_running_fps_, 2.0f, 60.0f, "%.0f");
    ImGui::TreePop();
  }
  int id = view_options_.focus_id ? static_cast<int>(*view_options_.focus_id) : -1;
  if (ImGui::InputInt("focus id", &id) && s != nullptr) {
    if (id >= 0 && static_cast<std::size_t>(id) < s->size()) {
      view_options_.focus_id = static_cast<Index>(id);
    } else {
      view_options_.focus_id.reset();
    }
    teach_step_ = 1 << 30;
    changed = true;
  }
  if (ImGui::Button("auto focus") && s != nullptr) {
    Particles p;  // auto_focus_id reads positions and radii only
    p.position = s->position;
    p.radius = s->radius;
    p.id = s->id;
    view_options_.focus_id = render::auto_focus_id(p);
    changed = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("no focus")) {
    view_options_.focus_id.reset();
    view_options_.zoom_to_focus = false;
    changed = true;
  }
  ImGui::Checkbox("inset", &inset_on_);
  ImGui::SameLine();
  if (ImGui::Checkbox("zoom to focus", &view_options_.zoom_to_focus)) {
    changed = true;
    if (!view_options_.zoom_to_focus) camera_changed(true);
  }
  if (view_options_.focus_id && s != nullptr && s->focus_visit) {
    const SearchVisit& v = *s->focus_visit;
    ImGui::Text("focus %u: cells %zu, tested %zu, contacts %zu",
                static_cast<unsigned>(*view_options_.focus_id), v.cells_visited, v.pairs_tested,
                v.contacts.size());
  }
  if (changed) push_view_options();
  ImGui::End();
}

void GuiApp::panel_export(const FrameSnapshot* s) {
  place(-370.0f, -230.0f, 360);
  ImGui::Begin("Export");
  ImGui::InputText("PNG", &png_path_);
  ImGui::SameLine();
  if (ImGui::Button("save##png") && s != nullptr) grab_view_ = true;
  ImGui::InputText("VTU dir", &vtu_dir_);
  ImGui::SameLine();
  if (ImGui::Button("save##vtu")) {
    try {
      const std::string dir = vtu_dir_;
      std::size_t written = 0;
      sim_->with_simulation([&](const Simulation& sim) {
        render::VtuSeriesWriter writer(dir, {});
        writer.write_frame(sim);
        written = writer.frames();
      });
      export_message_ = fmt::format("wrote {}/particles_000000.vtu ({} frame)", dir, written);
    } catch (const std::exception& e) {
      export_message_ = e.what();
    }
  }
  ImGui::InputText("movie", &movie_path_);
  ImGui::SameLine();
  if (!movie_frames_) {
    if (ImGui::Button("start")) {
      try {
        movie_frames_ = std::make_unique<render::FrameWriter>(
            std::filesystem::path(movie_path_).replace_extension("") += "_frames");
        export_message_ = "recording a frame per snapshot";
      } catch (const std::exception& e) {
        export_message_ = e.what();
      }
    }
  } else if (ImGui::Button("stop")) {
    try {
      render::MovieOptions mo;
      mo.frames_dir = movie_frames_->directory();
      mo.frames = movie_frames_->frames_written();
      const auto file = render::write_movie(mo, movie_path_);
      export_message_ = fmt::format("wrote {} ({} frames)", file.string(), mo.frames);
    } catch (const std::exception& e) {
      export_message_ = e.what();
    }
    movie_frames_.reset();
  }
  if (!export_message_.empty()) ImGui::TextWrapped("%s", export_message_.c_str());
  ImGui::End();
}

void GuiApp::panel_teach(const FrameSnapshot* s) {
  place(350, 10, 420);
  ImGui::SetNextWindowCollapsed(!teach_, ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Teaching: one particle's search, cell by cell")) {
    if (teach_) {
      teach_ = false;
      push_wish();
    }
    ImGui::End();
    return;
  }
  if (!teach_) {
    teach_ = true;
    push_wish();
  }
  if (!view_options_.focus_id || s == nullptr || s->compare_visits.empty()) {
    ImGui::TextWrapped("Click a particle (or set a focus id) to walk through its search.");
    ImGui::End();
    return;
  }
  std::vector<const char*> names;
  for (const MethodVisit& m : s->compare_visits) names.push_back(m.method.c_str());
  if (ImGui::Combo("method", &teach_method_, names.data(), static_cast<int>(names.size()))) {
    teach_step_ = teach_play_ || teach_cycle_ ? 0 : 1 << 30;
  }
  ImGui::SameLine();
  if (ImGui::Checkbox("m1..m5 in turn", &teach_cycle_) && teach_cycle_) teach_step_ = 0;
  display_snapshot(*s);  // builds the walk for this method
  const int steps = static_cast<int>(walk_->steps());
  if (ImGui::Button("<")) teach_step_ = std::max(0, teach_step_ - 1);
  ImGui::SameLine();
  if (ImGui::Button(">")) teach_step_ = std::min(steps, teach_step_ + 1);
  ImGui::SameLine();
  if (ImGui::Checkbox("play", &teach_play_) && teach_play_) teach_step_ = 0;
  ImGui::SameLine();
  ImGui::SliderInt("cell", &teach_step_, 0, steps);
  const double t = last_frame_time_;
  if ((teach_play_ || teach_cycle_) && t - teach_last_advance_ > 0.25) {
    teach_last_advance_ = t;
    if (teach_step_ < steps) {
      ++teach_step_;
    } else if (teach_cycle_) {
      teach_method_ = (teach_method_ + 1) % static_cast<int>(names.size());
      teach_step_ = 0;
    }
  }
  const TeachCounts c = walk_->counts(static_cast<std::size_t>(teach_step_));
  const SearchVisit& whole = s->compare_visits[static_cast<std::size_t>(teach_method_)].visit;
  ImGui::Text("%s, particle %u (r = %.3g mm)", names[static_cast<std::size_t>(teach_method_)],
              static_cast<unsigned>(*view_options_.focus_id), 1000.0 * s->radius[*s->focus_index]);
  ImGui::Text("cells visited %zu / %zu   candidates %zu / %zu   contacts %zu / %zu", c.cells,
              whole.cells_visited, c.candidates, whole.pairs_tested, c.contacts,
              whole.contacts.size());
  if (ImGui::BeginTable("all", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
    for (const char* h : {"method", "cells", "tested", "contacts"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (const MethodVisit& m : s->compare_visits) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(m.method.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%zu", m.visit.cells_visited);
      ImGui::TableNextColumn();
      ImGui::Text("%zu", m.visit.pairs_tested);
      ImGui::TableNextColumn();
      ImGui::Text("%zu", m.visit.contacts.size());
    }
    ImGui::EndTable();
  }
  ImGui::TextWrapped(
      "yellow: own cell, green: visited half stencil, red: skipped half (partners there find "
      "this particle), blue: method 2's far ring, orange: candidates, magenta: contacts");
  ImGui::End();
}

}  // namespace drumlab::gui
