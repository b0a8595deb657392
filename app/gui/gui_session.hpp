#pragma once
// The scene and the session as the GUI runs them, and the GUI's clock.
#include <string>

#include "app/gui/gui_options.hpp"
#include "engine/session/run_session.hpp"

namespace drumlab::gui {

/// The scene as the GUI runs it: the stability check (and so the settling's snapshots) at least
/// every 50 steps, so the settling shows as it happens. Checks are read-only: the trajectory is
/// the same as with the scene's own interval.
SceneConfig gui_scene(const std::string& file);
/// The same interval for a scene edited in the GUI.
SceneConfig with_gui_checks(SceneConfig scene);

/// Seconds on a steady clock.
double now_seconds();
/// The session options of the GUI's flags (scene, method, settle time).
SessionOptions session_options(const GuiOptions& o);

}  // namespace drumlab::gui
