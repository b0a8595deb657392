#pragma once
// The teaching figure: the five cell-grid methods side by side, each showing the same particle's
// search in the same state (own cell, visited stencil, skipped half, candidates, contacts) and
// titled with the cells it visited and the pairs it tested.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/scene_config.hpp"
#include "engine/simulation.hpp"
#include "render/image.hpp"

namespace drumlab::render {

struct TeachPanel {
  std::string method;
  std::size_t cells_visited = 0;  ///< cells of the drawn trace (own cell included)
  std::size_t pairs_tested = 0;   ///< candidates of the drawn trace
  std::size_t contacts = 0;       ///< contacts this particle's search finds (its half of its pairs)
};

struct TeachFigure {
  Index particle_id = 0;
  std::vector<TeachPanel> panels;  ///< m1..m5
  Image image;                     ///< the panels side by side
};

/// The paper methods shown, in order.
std::vector<std::string> teach_methods();

/// The state a panel shows: the scene filled (its [fill] kind) and settled (drum at rest; a
/// RunSession, engine/session/run_session.hpp) with `method` as its
/// search, so the last step's per-particle counters are that method's. Every method gives the
/// same trajectory, hence the same state.
std::unique_ptr<Simulation> teach_simulation(SceneConfig scene, std::string_view method);

/// Renders the figure for the particle with stable id `particle_id` (default: auto_focus_id).
TeachFigure make_teach_figure(const SceneConfig& scene, std::optional<Index> particle_id,
                              int panel_width = 520, int panel_height = 600);

}  // namespace drumlab::render
