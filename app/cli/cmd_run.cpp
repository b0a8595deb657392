// drumlab run SCENE [--method M] [--steps N | --revolutions R] [--dt-factor F] [--threads N]
// drumlab demo      (the demo drum, scenes/drum_demo.toml)
#include "app/cli/commands.hpp"
#include "app/cli/run_session.hpp"
#include "app/cli/scene_setup.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "app/cli/render_observer.hpp"
#endif

namespace drumlab::cli {

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* run =
      app.add_subcommand("run", "Simulate a scene: fill, settle, turn the drum, report");
  run->add_option("scene", opt->scene, "scene file (TOML)")->required();
  add_run_options(run, *opt);
  run->callback([opt] { run_session(*opt); });

  auto demo_opt = std::make_shared<RunOptions>();
  CLI::App* demo = app.add_subcommand("demo", "Run the demo drum (scenes/drum_demo.toml)");
  add_run_options(demo, *demo_opt);
  demo->callback([demo_opt] {
    demo_opt->scene = shipped_scene("drum_demo.toml");
#ifdef DRUMLAB_WITH_RENDER
    // Renders out/demo/frames/*.png and out/demo/drum_demo.mp4 while it runs.
    if (demo_opt->frames == 0 && demo_opt->every == 0) demo_opt->frames = 100;
    auto renderer = make_demo_renderer("out/demo");
    FrameObserver* observers[] = {renderer.get()};
    run_session(*demo_opt, observers);
#else
    run_session(*demo_opt);
#endif
  });
}

}  // namespace drumlab::cli
