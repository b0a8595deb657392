#include "app/gui/teaching.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <imgui.h>

#include "app/gui/gui_window.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab::gui {

Teaching::Teaching(const GuiOptions& options)
    : on_(options.teach), methods_(cell_grid_method_names()) {
  if (!options.teach_method.empty()) {
    const auto t = std::find(methods_.begin(), methods_.end(), options.teach_method);
    if (t == methods_.end()) {
      throw InputError(fmt::format("--teach-method: '{}' is not one of {}", options.teach_method,
                                   fmt::join(methods_, ", ")));
    }
    method_ = static_cast<int>(t - methods_.begin());
  }
  if (options.teach_cells >= 0) step_ = options.teach_cells;
}

std::vector<std::string> Teaching::compare_methods(bool focus) const {
  return on_ && focus ? methods_ : std::vector<std::string>{};
}

FrameSnapshot Teaching::display_snapshot(const FrameSnapshot& s, std::uint64_t generation) {
  if (!on_ || !s.focus_index || s.compare_visits.empty()) return s;
  method_ = std::clamp(method_, 0, static_cast<int>(s.compare_visits.size()) - 1);
  const MethodVisit& mv = s.compare_visits[static_cast<std::size_t>(method_)];
  if (!walk_ || walk_generation_ != generation || walk_method_ != method_) {
    walk_.emplace(mv.visit, s.position);
    walk_generation_ = generation;
    walk_method_ = method_;
  }
  FrameSnapshot d = s;
  step_ = std::min(step_, static_cast<int>(walk_->steps()));
  d.focus_visit = walk_->prefix(static_cast<std::size_t>(step_));
  if (!mv.visit.grids.empty()) d.grid = mv.visit.grids.front().geometry;
  d.search_name = mv.method + " (teaching)";
  return d;
}

std::string Teaching::report(const FrameSnapshot& s, std::uint64_t generation) {
  if (!on_ || !s.focus_index || s.compare_visits.empty()) return {};
  display_snapshot(s, generation);  // builds the walk for this method
  const TeachCounts c = walk_->counts(static_cast<std::size_t>(step_));
  const MethodVisit& mv = s.compare_visits[static_cast<std::size_t>(method_)];
  return fmt::format("teach {}: cells {} / {}, candidates {} / {}, contacts {} / {}", mv.method,
                     c.cells, mv.visit.cells_visited, c.candidates, mv.visit.pairs_tested,
                     c.contacts, mv.visit.contacts.size());
}

bool Teaching::panel(const GuiWindow& window, const FrameSnapshot* s, std::uint64_t generation,
                     std::optional<Index> focus_id, double now) {
  window.place(GuiWindow::kMargin, GuiWindow::kTeachingY, GuiWindow::kLeftPanels);
  ImGui::SetNextWindowCollapsed(!on_, ImGuiCond_FirstUseEver);
  const bool open = ImGui::Begin("Teaching: one particle's search, cell by cell");
  const bool changed = open != on_;
  on_ = open;
  if (!open) {
    ImGui::End();
    return changed;
  }
  if (!focus_id || s == nullptr || s->compare_visits.empty()) {
    ImGui::TextWrapped("Click a particle (or set a focus id) to walk through its search.");
    ImGui::End();
    return changed;
  }
  walk_controls(*s, generation, now);
  method_table(*s, focus_id);
  ImGui::TextWrapped(
      "yellow: own cell, green: visited half stencil, red: skipped half (partners there find "
      "this particle), blue: method 2's far ring, orange: candidates, magenta: contacts");
  ImGui::End();
  return changed;
}

void Teaching::walk_controls(const FrameSnapshot& s, std::uint64_t generation, double now) {
  std::vector<const char*> names;
  for (const MethodVisit& m : s.compare_visits) names.push_back(m.method.c_str());
  if (ImGui::Combo("method", &method_, names.data(), static_cast<int>(names.size()))) {
    step_ = play_ || cycle_ ? 0 : kWhole;
  }
  ImGui::SameLine();
  if (ImGui::Checkbox("m1..m5 in turn", &cycle_) && cycle_) step_ = 0;
  display_snapshot(s, generation);  // builds the walk for this method
  const int steps = static_cast<int>(walk_->steps());
  if (ImGui::Button("<")) step_ = std::max(0, step_ - 1);
  ImGui::SameLine();
  if (ImGui::Button(">")) step_ = std::min(steps, step_ + 1);
  ImGui::SameLine();
  if (ImGui::Checkbox("play", &play_) && play_) step_ = 0;
  ImGui::SameLine();
  ImGui::SliderInt("cell", &step_, 0, steps);
  if ((play_ || cycle_) && now - last_advance_ > 0.25) {
    last_advance_ = now;
    if (step_ < steps) {
      ++step_;
    } else if (cycle_) {
      method_ = (method_ + 1) % static_cast<int>(names.size());
      step_ = 0;
    }
  }
}

void Teaching::method_table(const FrameSnapshot& s, std::optional<Index> focus_id) const {
  const TeachCounts c = walk_->counts(static_cast<std::size_t>(step_));
  const MethodVisit& shown = s.compare_visits[static_cast<std::size_t>(method_)];
  const SearchVisit& whole = shown.visit;
  ImGui::Text("%s, particle %u (r = %.3g mm)", shown.method.c_str(),
              static_cast<unsigned>(*focus_id), 1000.0 * s.radius[*s.focus_index]);
  ImGui::Text("cells visited %zu / %zu   candidates %zu / %zu   contacts %zu / %zu", c.cells,
              whole.cells_visited, c.candidates, whole.pairs_tested, c.contacts,
              whole.contacts.size());
  if (ImGui::BeginTable("all", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
    for (const char* h : {"method", "cells", "tested", "contacts"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (const MethodVisit& m : s.compare_visits) {
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
}

}  // namespace drumlab::gui
