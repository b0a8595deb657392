// drumlab teach --out FILE.png [--particle ID]: the five methods' search of one particle of
// scenes/teach_stencil.toml, side by side.
#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "app/cli/scene_setup.hpp"
#include "engine/session/run_session.hpp"
#include "render/frame_writer.hpp"
#include "render/teach_figure.hpp"

namespace drumlab::cli {

namespace {

struct TeachArgs {
  std::string out;
  std::string scene;
  std::optional<Index> particle;
};

void run_teach(const TeachArgs& a) {
  const std::filesystem::path out(a.out);
  const auto dir = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(dir)) {
    throw InputError(fmt::format("--out {}: the directory {} does not exist", a.out, dir.string()));
  }
  const SceneConfig scene = load_dynamic_scene(a.scene);
  const render::TeachFigure fig = render::make_teach_figure(scene, a.particle);
  render::write_png(fig.image, out);
  fmt::print("teach             particle id {} of {} ({})\n", fig.particle_id, scene.name, a.scene);
  for (const render::TeachPanel& p : fig.panels) {
    fmt::print("{:<4} cells visited {:>4}   pairs tested {:>4}   contacts found {:>2}\n", p.method,
               p.cells_visited, p.pairs_tested, p.contacts);
  }
  fmt::print("figure            {} ({}x{})\n", a.out, fig.image.width, fig.image.height);
}

}  // namespace

void add_teach_command(CLI::App& app) {
  auto args = std::make_shared<TeachArgs>();
  CLI::App* cmd = app.add_subcommand(
      "teach", "One figure: the five search methods side by side for the same particle");
  cmd->add_option("--out", args->out, "PNG file")->required();
  cmd->add_option("--particle", args->particle, "particle id (default: a large one mid-bed)");
  cmd->add_option("--scene", args->scene, "scene (default scenes/teach_stencil.toml)");
  cmd->callback([args] {
    if (args->scene.empty()) args->scene = shipped_scene("teach_stencil.toml");
    run_teach(*args);
  });
}

}  // namespace drumlab::cli
