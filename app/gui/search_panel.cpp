#include "app/gui/search_panel.hpp"

#include <algorithm>
#include <cfloat>

#include <fmt/format.h>
#include <imgui.h>

#include "app/gui/gui_window.hpp"
#include "engine/search/search_methods.hpp"

namespace drumlab::gui {

namespace {

std::vector<std::string> all_methods() {
  std::vector<std::string> names = search_method_names();
  for (const std::string& b : verlet_builder_names()) {
    const std::string v = verlet_method_name(b);
    if (std::find(names.begin(), names.end(), v) == names.end()) names.push_back(v);
  }
  names.emplace_back("auto");
  return names;
}

void plot(const char* label, const History& h, const char* unit) {
  if (h.values.empty()) return;
  std::vector<float> v(h.values.begin(), h.values.end());
  const std::string overlay = fmt::format("{:.3g} {}", v.back(), unit);
  ImGui::PlotLines(label, v.data(), static_cast<int>(v.size()), 0, overlay.c_str(), FLT_MAX,
                   FLT_MAX, ImVec2(0, 50));
}

}  // namespace

SearchPanel::SearchPanel(const std::string& active) : methods_(all_methods()) {
  const auto it = std::find(methods_.begin(), methods_.end(), active);
  method_index_ = it == methods_.end() ? 0 : static_cast<int>(it - methods_.begin());
}

void SearchPanel::panel(const GuiWindow& window, SimThread& sim, const FrameSnapshot* s) {
  const float height =
      ImGui::GetIO().DisplaySize.y + GuiWindow::kInsetY - 2.0f * GuiWindow::kMargin;
  window.place(GuiWindow::kRightX, GuiWindow::kMargin, GuiWindow::kRightPanels, height);
  ImGui::Begin("Search");
  std::vector<const char*> names;
  for (const std::string& m : methods_) names.push_back(m.c_str());
  if (ImGui::Combo("method", &method_index_, names.data(), static_cast<int>(names.size()))) {
    sim.switch_method(methods_[static_cast<std::size_t>(method_index_)]);
  }
  if (s != nullptr) {
    counters(*s);
    plots(*s);
  }
  ImGui::End();
}

void SearchPanel::counters(const FrameSnapshot& s) const {
  ImGui::TextWrapped("active: %s", s.search_name.c_str());
  const double n = std::max<double>(1.0, static_cast<double>(s.size()));
  const double cells = static_cast<double>(s.counters.cells_visited);
  if (!s.lists_pairs) {
    ImGui::Text("last step: cells %.0f (%.1f / particle)", cells, cells / n);
  } else if (cells == 0.0) {  // a Verlet step without a rebuild opens no cell
    ImGui::TextUnformatted("last step: list reused (no rebuild)");
  } else {
    ImGui::Text("last step: list rebuilt, %.0f builder cells (%.1f / particle)", cells, cells / n);
  }
  ImGui::Text("pairs tested %llu (%.1f / particle)",
              static_cast<unsigned long long>(s.counters.pairs_tested),
              static_cast<double>(s.counters.pairs_tested) / n);
  ImGui::Text("pairs found %llu", static_cast<unsigned long long>(s.counters.pairs_found));
  if (ImGui::BeginTable("classes", 5, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
    for (const char* h :
         {"class", "N", s.lists_pairs ? "rebuild cells/p" : "cells/p", "tests/p", "contacts/p"}) {
      ImGui::TableSetupColumn(h);
    }
    ImGui::TableHeadersRow();
    for (const ClassCounters& c : s.per_class) {
      const double k = std::max<double>(1.0, static_cast<double>(c.particles));
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%s %.3g mm", c.name.c_str(), 1000.0 * c.radius);  // a distribution: mean
      ImGui::TableNextColumn();
      ImGui::Text("%zu", c.particles);
      ImGui::TableNextColumn();
      if (s.lists_pairs && c.cells_visited == 0) {
        ImGui::TextUnformatted("reused");
      } else {
        ImGui::Text("%.1f", static_cast<double>(c.cells_visited) / k);
      }
      ImGui::TableNextColumn();
      ImGui::Text("%.1f", static_cast<double>(c.pairs_tested) / k);
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", static_cast<double>(c.contacts) / k);
    }
    ImGui::EndTable();
  }
}

void SearchPanel::plots(const FrameSnapshot& s) const {
  const StepTimers& split = history_.recent_split;
  const double total = std::max(1e-12, split.total());
  ImGui::Text("step time: search %.0f%%  forces %.0f%%", 100.0 * split.search / total,
              100.0 * split.forces / total);
  ImGui::Text("           walls %.0f%%  integration %.0f%%", 100.0 * split.walls / total,
              100.0 * (split.integration + split.reorder) / total);
  plot(s.lists_pairs ? "rebuild cells/p" : "cells/p", history_.cells_per_particle, "");
  plot("tests/p", history_.tests_per_particle, "");
  plot("found/p", history_.contacts_per_particle, "");
  plot("ms/step", history_.step_ms, "ms");
  if (s.diagnostics) {
    const Diagnostics& d = *s.diagnostics;
    ImGui::Text("kinetic %.4g J  rotational %.4g J", d.kinetic_energy, d.rotational_energy);
    ImGui::Text("potential %.4g J  elastic %.4g J", d.potential_energy, d.elastic_energy);
    ImGui::Text("max overlap %.3f r  outside %zu", d.max_overlap_ratio, d.outside_drum);
    plot("kinetic", history_.kinetic, "J");
  }
}

}  // namespace drumlab::gui
