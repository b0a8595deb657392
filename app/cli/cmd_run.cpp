// drumlab run SCENE [--method M] [--steps N | --revolutions R] [--dt-factor F] [--threads N]
//              [--vtu DIR [--contacts-vtk] [--grid-vtk]] [--h5 FILE] [--every K]
//              [--checkpoint FILE [--checkpoint-every K]] [--restart FILE]
// drumlab demo      (the demo drum, scenes/drum_demo.toml; VTU series in out/demo/vtu/)
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
  add_run_arguments(run, *opt);  // the same as drumlab-mpi run's (app/run/run_options.hpp)
  run->callback([opt] { run_session(*opt); });

  auto demo_opt = std::make_shared<RunOptions>();
#ifdef DRUMLAB_WITH_RENDER
  demo_opt->vtu_dir = "out/demo/vtu";  // the demo's VTU series for ParaView (--vtu DIR moves it)
#endif
  CLI::App* demo = app.add_subcommand("demo", "Run the demo drum (scenes/drum_demo.toml)");
  add_run_options(demo, *demo_opt);
  demo->add_option("--every", demo_opt->every, "steps between output frames")
      ->check(CLI::PositiveNumber);
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
