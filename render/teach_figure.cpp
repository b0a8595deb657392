#include "render/teach_figure.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/search/search_methods.hpp"
#include "engine/session/run_session.hpp"
#include "render/drum_view.hpp"
#include "render/offscreen_context.hpp"

namespace drumlab::render {

namespace {

/// Copies `panel` into columns [x0, x0 + panel.width) of `figure`.
void blit(const Image& panel, Image& figure, int x0) {
  const std::size_t row = 3 * static_cast<std::size_t>(panel.width);
  for (int y = 0; y < panel.height; ++y) {
    std::copy_n(panel.rgb.data() + row * static_cast<std::size_t>(y), row,
                figure.rgb.data() +
                    3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(figure.width) +
                         static_cast<std::size_t>(x0)));
  }
}

std::string panel_title(const Simulation& sim, const TeachPanel& p) {
  std::string what(sim.search().description());
  if (const auto colon = what.find(": "); colon != std::string::npos) what.erase(0, colon + 2);
  return fmt::format(
      "{}  cells visited {}  pairs tested {}  found {}\n{}\n"
      "crimson own cell | lime visited | dark red skipped half\n"
      "blue m2 far ring | cyan tested | magenta contact",
      p.method, p.cells_visited, p.pairs_tested, p.contacts, what);
}

}  // namespace

std::vector<std::string> teach_methods() {
  return cell_grid_method_names();
}

std::unique_ptr<Simulation> teach_simulation(SceneConfig scene, std::string_view method) {
  SessionOptions options;
  options.method = std::string(method);
  RunSession session(std::move(scene), options);  // the scene's fill, random or from a file
  session.settle();
  return session.release_simulation();
}

TeachFigure make_teach_figure(const SceneConfig& scene, std::optional<Index> particle_id,
                              int panel_width, int panel_height) {
  TeachFigure fig;
  const auto methods = teach_methods();
  fig.image.width = panel_width * static_cast<int>(methods.size());
  fig.image.height = panel_height;
  fig.image.rgb.assign(3 * static_cast<std::size_t>(fig.image.width) * panel_height, 0);
  for (std::size_t k = 0; k < methods.size(); ++k) {
    const auto sim = teach_simulation(scene, methods[k]);
    if (k == 0) {
      fig.particle_id = particle_id ? *particle_id : auto_focus_id(sim->particles());
      index_of_id(sim->particles(), fig.particle_id);  // throws for an unknown id
    }
    ViewOptions opt;
    opt.width = panel_width;
    opt.height = panel_height;
    opt.focus_id = fig.particle_id;
    opt.zoom_to_focus = true;
    opt.overlay = false;
    opt.neutral_particles = true;
    opt.title = " ";                                      // replaced below once the trace is known
    OffscreenContext context(panel_width, panel_height);  // outlives the view
    DrumView view(opt, context);
    view.render(*sim);
    const SearchVisit visit = view.focus_visit();
    TeachPanel panel;
    panel.method = methods[k];
    panel.cells_visited = visit.cells_visited;
    panel.pairs_tested = visit.pairs_tested;
    panel.contacts = visit.contacts.size();
    view.set_title(panel_title(*sim, panel));
    blit(view.render(*sim), fig.image, panel_width * static_cast<int>(k));
    fig.panels.push_back(panel);
  }
  return fig;
}

}  // namespace drumlab::render
