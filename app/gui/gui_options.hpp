#pragma once
// The command line of drumlab-gui: the scene, the window, and the headless driving used by tests
// and benchmarks (--frames N --screenshot FILE.png, --bench).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/sim_thread.hpp"

namespace drumlab::gui {

struct GuiOptions {
  std::string scene;  ///< the scene file (default: scenes/drum_demo.toml)
  std::string method;
  std::optional<Index> focus_id;
  std::string focus;  ///< "auto" or an id, as given
  std::optional<ScheduledSwitch> switch_at;
  std::string color_by = "size";
  std::string camera = "axis";
  double settle_time = -1.0;  ///< < 0: the scene's
  std::uint64_t steps_per_frame = 10;
  int threads = 1;
  std::string team = "adaptive";  ///< with threads > 1: adaptive or fixed (TeamChooser)
  int width = 1400;
  int height = 900;
  // Headless driving.
  std::uint64_t frames = 0;  ///< > 0: run this many frames (steps_per_frame steps each), then exit
  std::string screenshot;    ///< the whole window as PNG, at the end
  std::string checkpoint;    ///< the final state (HDF5 checkpoint), at the end
  bool zoom_to_focus = false;
  bool teach = false;        ///< open the teaching panel
  std::string teach_method;  ///< the teaching panel's method (default: the first, m1)
  int teach_cells = -1;      ///< cells of the walk shown (< 0: the whole search)
  bool bench = false;
  std::vector<std::string> edits;  ///< KEY=VALUE edits of the scene panel's fields (apply_edit)
  std::string save_scene;          ///< headless: save the edited scene as TOML at the end
  /// Headless, before the last frame: turn the camera (degrees azimuth, elevation), zoom, and
  /// click the window pixel (column, row from the top) to focus the particle there.
  std::optional<std::array<double, 2>> orbit;
  double zoom = 1.0;
  std::optional<std::array<double, 2>> pick;
  bool inset = true;  ///< the focus inset (a second view framing the focus particle's search)
};

/// One edit of the scene panel's fields, as "KEY=VALUE": omega (rad/s), rpm, friction,
/// restitution, wall_friction, count, fill_fraction, seed, settle_time; then the whole scene is
/// validated (engine/scene/scene_validation.hpp). Throws InputError naming --edit and the scene
/// key for an unknown key, a value that is not a number (count and seed: a whole number) or a
/// value out of its range.
void apply_edit(SceneConfig& scene, const std::string& edit);

/// "K:METHOD" -> the switch; throws InputError naming --switch-at otherwise (and for an unknown
/// method).
ScheduledSwitch parse_switch_at(const std::string& text);
/// Throws InputError naming `flag` if `name` is not a search method (or "auto").
void check_method(const std::string& name, const std::string& flag);

}  // namespace drumlab::gui
