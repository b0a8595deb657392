#pragma once
// The Scene panel: the scene file's scene with the user's edits (drum speed, friction,
// restitution, particle classes, fill), restarted from or saved as TOML; a scene's triangle walls
// listed as the file has them.
#include <string>
#include <vector>

#include "app/gui/sim_thread.hpp"

namespace drumlab::gui {

class GuiWindow;

class SceneEditor {
 public:
  /// The scene of `file` (as the file has it, not the GUI's run of it) with `edits` (--edit
  /// KEY=VALUE, apply_edit) applied; throws InputError for bad ones.
  SceneEditor(std::string file, const std::vector<std::string>& edits);
  const SceneConfig& scene() const { return edited_; }
  /// Drops the edits: the file's scene again.
  void reset();
  /// Saves the edited scene as TOML (engine/scene/scene_writer.hpp; atomic).
  void save(const std::string& file) const;
  /// The panel: its fields, "Restart from edited scene" (restarts `sim`) and "Save".
  void panel(const GuiWindow& window, SimThread& sim);

 private:
  void class_fields();
  void fill_fields();
  /// The triangle walls ([[wall.mesh]], [[wall.lifters]]), read only: they are the file's.
  void mesh_lines() const;

  std::string file_;
  SceneConfig edited_;
  std::string message_;
  std::string save_path_ = "out/gui/edited_scene.toml";
};

}  // namespace drumlab::gui
