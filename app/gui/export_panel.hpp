#pragma once
// The Export panel: the view as PNG, the simulation's state as VTU, and a movie (a frame per new
// snapshot, encoded when stopped).
#include <cstdint>
#include <memory>
#include <string>

#include "app/gui/sim_thread.hpp"
#include "render/frame_writer.hpp"

namespace drumlab::gui {

class GuiWindow;
class MainView;

class ExportPanel {
 public:
  void panel(const GuiWindow& window, SimThread& sim, const FrameSnapshot* s);
  /// The view must be rendered at full size this frame (a PNG or a movie frame is taken).
  bool wants_full_view() const { return grab_view_ || movie_frames_ != nullptr; }
  /// After the view rendered snapshot `generation`: saves the PNG if asked, and a movie frame.
  void take(MainView& view, std::uint64_t generation);
  /// The panel's message line (errors of the view too).
  void set_message(std::string message) { message_ = std::move(message); }

 private:
  void save_vtu(SimThread& sim);
  void movie_button();

  std::string png_path_ = "out/gui/view.png";
  std::string vtu_dir_ = "out/gui/vtu";
  std::string movie_path_ = "out/gui/movie.mp4";
  std::string message_;
  bool grab_view_ = false;
  std::unique_ptr<render::FrameWriter> movie_frames_;
  std::uint64_t movie_last_generation_ = 0;
};

}  // namespace drumlab::gui
