#pragma once
// The rendering observer of `render` and `demo`: renders a frame of the drum at each scheduled
// frame, writes it as PNG, and encodes the movie at the end. Only built with DRUMLAB_WITH_RENDER.
#include <filesystem>
#include <memory>
#include <optional>

#include "app/cli/run_session.hpp"
#include "render/drum_view.hpp"

namespace drumlab::cli {

struct RenderOutput {
  std::filesystem::path frames_dir;
  std::optional<std::filesystem::path> movie;
  render::ViewOptions view;
  bool focus_auto = false;  ///< pick the focus particle on the first frame
};

/// Creates the frames directory now (InputError for a bad path); VTK objects are created only
/// when the first frame is due.
std::unique_ptr<FrameObserver> make_render_observer(const RenderOutput& output);

/// The demo's renderer: OUT/frames/*.png and OUT/drum_demo.mp4 at 1280x720, coloured by speed.
std::unique_ptr<FrameObserver> make_demo_renderer(const std::filesystem::path& out_dir);

}  // namespace drumlab::cli
