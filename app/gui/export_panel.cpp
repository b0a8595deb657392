#include "app/gui/export_panel.hpp"

#include <filesystem>

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "app/gui/gui_window.hpp"
#include "app/gui/main_view.hpp"
#include "render/movie_writer.hpp"
#include "render/vtu_series_writer.hpp"

namespace drumlab::gui {

void ExportPanel::panel(const GuiWindow& window, SimThread& sim, const FrameSnapshot* s) {
  window.place(GuiWindow::kRightX, GuiWindow::kExportY, GuiWindow::kRightPanels);
  ImGui::Begin("Export");
  ImGui::InputText("PNG", &png_path_);
  ImGui::SameLine();
  if (ImGui::Button("save##png") && s != nullptr) grab_view_ = true;
  ImGui::InputText("VTU dir", &vtu_dir_);
  ImGui::SameLine();
  if (ImGui::Button("save##vtu")) save_vtu(sim);
  ImGui::InputText("movie", &movie_path_);
  ImGui::SameLine();
  movie_button();
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
  ImGui::End();
}

void ExportPanel::save_vtu(SimThread& sim) {
  try {
    const std::string dir = vtu_dir_;
    std::size_t written = 0;
    sim.with_simulation([&](const Simulation& simulation) {
      render::VtuSeriesWriter writer(dir, {});
      writer.write_frame(simulation);
      written = writer.frames();
    });
    message_ = fmt::format("wrote {}/particles_000000.vtu ({} frame)", dir, written);
  } catch (const std::exception& e) {
    message_ = e.what();
  }
}

void ExportPanel::movie_button() {
  if (!movie_frames_) {
    if (!ImGui::Button("start")) return;
    try {
      movie_frames_ = std::make_unique<render::FrameWriter>(
          std::filesystem::path(movie_path_).replace_extension("") += "_frames");
      message_ = "recording a frame per snapshot";
    } catch (const std::exception& e) {
      message_ = e.what();
    }
    return;
  }
  if (!ImGui::Button("stop")) return;
  try {
    render::MovieOptions mo;
    mo.frames_dir = movie_frames_->directory();
    mo.frames = movie_frames_->frames_written();
    const auto file = render::write_movie(mo, movie_path_);
    message_ = fmt::format("wrote {} ({} frames)", file.string(), mo.frames);
  } catch (const std::exception& e) {
    message_ = e.what();
  }
  movie_frames_.reset();
}

void ExportPanel::take(MainView& view, std::uint64_t generation) {
  if (grab_view_) {  // the view alone, without the panels
    grab_view_ = false;
    try {
      render::write_png(view.read_image(), png_path_);
      message_ = fmt::format("wrote {}", png_path_);
    } catch (const std::exception& e) {
      message_ = e.what();
    }
  }
  if (movie_frames_ && generation != movie_last_generation_) {
    movie_last_generation_ = generation;
    movie_frames_->write(view.read_image(), movie_frames_->frames_written());
  }
}

}  // namespace drumlab::gui
