// drumlab render SCENE --out DIR [--frames N] [--every K] [--movie FILE] [--size WxH]
//   [--color-by size|speed|omega|id|coordination|agglomerate] [--grid] [--focus ID|auto] [--camera
//   axis|iso] [--frame carrier|lab|drum] (a planetary drum's pictures: the arm's frame by default)
#include <chrono>
#include <cstdio>
#include <regex>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/cli/commands.hpp"
#include "app/cli/render_observer.hpp"
#include "app/cli/scene_setup.hpp"
#include "app/run/count_option.hpp"
#include "engine/search/search_methods.hpp"
#include "render/frame_writer.hpp"
#include "render/movie_writer.hpp"
#include "render/offscreen_context.hpp"

namespace drumlab::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// f(), with the command-line flag an InputError of the render library came from put in front.
template <class F>
auto with_flag(std::string_view flag, F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", flag, e.what()));
  }
}

class RenderObserver final : public FrameObserver {
 public:
  explicit RenderObserver(const RenderOutput& out) : out_(out), frames_(out.frames_dir) {
    if (out_.movie) {
      const fs::path dir = out_.movie->has_parent_path() ? out_.movie->parent_path() : ".";
      std::error_code ec;
      fs::create_directories(dir, ec);
      if (!fs::is_directory(dir)) {
        throw InputError(
            fmt::format("--movie {}: cannot create {}", out_.movie->string(), dir.string()));
      }
    }
  }

  void on_frame(const Simulation& sim, std::uint64_t frame) override {
    if (!view_) {
      if (out_.focus_auto) {
        out_.view.focus_id =
            with_flag("--focus auto", [&] { return render::auto_focus_id(sim.particles()); });
      }
      context_ = std::make_unique<render::OffscreenContext>(out_.view.width, out_.view.height);
      view_ = std::make_unique<render::DrumView>(out_.view, *context_);
    }
    const auto t0 = Clock::now();
    // The view's input errors come from the focus particle or the grid it was asked to draw.
    const char* flags = !out_.view.focus_id ? "--grid"
                        : out_.view.grid    ? "--grid/--focus"
                                            : "--focus";
    const render::Image image = with_flag(flags, [&] { return view_->render(sim); });
    const auto t1 = Clock::now();
    frames_.write(image, frame);
    render_s_ += std::chrono::duration<double>(t1 - t0).count();
    write_s_ += std::chrono::duration<double>(Clock::now() - t1).count();
  }

  void on_finish(const Simulation& sim) override {
    const auto n = frames_.frames_written();
    if (n == 0) return;
    fmt::print(
        "\nrender            {} frames {}x{} of {} particles: {:.2f} frames/s rendering ({:.0f} "
        "ms/frame), PNG {:.0f} ms/frame -> {}\n",
        n, out_.view.width, out_.view.height, sim.particles().size(),
        static_cast<double>(n) / render_s_, 1000.0 * render_s_ / static_cast<double>(n),
        1000.0 * write_s_ / static_cast<double>(n), frames_.directory().string());
    if (!out_.movie) return;
    render::MovieOptions movie;
    movie.frames_dir = frames_.directory();
    movie.frames = n;
    const auto t0 = Clock::now();
    const fs::path written = render::write_movie(movie, *out_.movie);
    fmt::print("movie             {} ({:.1f} s to encode)\n", written.string(),
               std::chrono::duration<double>(Clock::now() - t0).count());
  }

 private:
  RenderOutput out_;
  render::FrameWriter frames_;
  std::unique_ptr<render::OffscreenContext> context_;  // outlives view_
  std::unique_ptr<render::DrumView> view_;
  double render_s_ = 0.0;
  double write_s_ = 0.0;
};

std::pair<int, int> parse_size(const std::string& s) {
  std::smatch m;
  static const std::regex re(R"((\d{2,5})x(\d{2,5}))");
  if (!std::regex_match(s, m, re)) {
    throw InputError(fmt::format("--size: expected WxH such as 1280x720, got '{}'", s));
  }
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 16 || h < 16 || w > 8192 || h > 8192) {
    throw InputError(fmt::format("--size: {}x{} is outside 16..8192", w, h));
  }
  return {w, h};
}

struct RenderArgs {
  std::string out, movie, size = "1280x720", color_by = "size", focus, camera = "axis";
  bool grid = false;
};

RenderOutput make_output(const RenderArgs& a) {
  RenderOutput out;
  out.frames_dir = a.out;
  if (!a.movie.empty()) out.movie = a.movie;
  std::tie(out.view.width, out.view.height) = parse_size(a.size);
  out.view.color_by = with_flag("--color-by", [&] { return render::parse_color_by(a.color_by); });
  out.view.camera = with_flag("--camera", [&] { return render::parse_camera(a.camera); });
  out.view.grid = a.grid;
  if (a.focus == "auto") {
    out.focus_auto = true;
  } else if (!a.focus.empty()) {
    if (a.focus.find_first_not_of("0123456789") != std::string::npos || a.focus.size() > 9) {
      throw InputError(fmt::format("--focus: expected a particle id or 'auto', got '{}'", a.focus));
    }
    out.view.focus_id = static_cast<Index>(std::stoul(a.focus));
  }
  return out;
}

}  // namespace

std::unique_ptr<FrameObserver> make_render_observer(const RenderOutput& output) {
  return std::make_unique<RenderObserver>(output);
}

std::unique_ptr<FrameObserver> make_demo_renderer(const fs::path& out_dir) {
  RenderOutput out;
  out.frames_dir = out_dir / "frames";
  out.movie = out_dir / "drum_demo.mp4";
  out.view.color_by = render::ColorBy::speed;
  return make_render_observer(out);
}

void add_render_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd =
      app.add_subcommand("render", "Simulate a scene and render PNG frames and a movie");
  cmd->add_option("scene", opt->scene, "scene file (TOML)")->required();
  add_run_options(cmd, *opt);
  cmd->add_option("--out", args->out, "directory for the PNG frames")->required();
  auto* frames = cmd->add_option("--frames", opt->frames, "frames over the turning phase")
                     ->check(whole_count());
  cmd->add_option("--every", opt->every, "steps between frames")
      ->check(whole_count())
      ->excludes(frames);
  cmd->add_option("--movie", args->movie, "movie file (.mp4 with ffmpeg, else .ogv)");
  cmd->add_option("--size", args->size, "frame size WxH (default 1280x720)");
  cmd->add_option("--color-by", args->color_by,
                  "size, speed, omega, id, coordination or agglomerate");
  cmd->add_flag("--grid", args->grid, "colour the search grid's cells by occupancy");
  cmd->add_option("--focus", args->focus, "show one particle's search: its id, or auto");
  cmd->add_option("--camera", args->camera, "axis (along the drum axis) or iso");
  cmd->callback([opt, args] {
    RenderOutput out = make_output(*args);
    out.view.granule = opt->granule.criterion;
    if (!opt->frame.empty()) out.view.frame = paraview::parse_view_frame(opt->frame, "--frame");
    if (args->grid) {  // fail now, not after settling; --focus shows every method's search
      const std::string method =
          opt->method.empty() ? load_dynamic_scene(opt->scene).search_method : opt->method;
      const auto parsed = parse_search_method(method);
      if (parsed && !parsed->method->draws_cells) {
        throw InputError(fmt::format(
            "--grid: search '{}' has no cells to draw; use {} or a Verlet list built by one",
            method, fmt::join(cell_grid_method_names(), ", ")));
      }
    }
    auto observer = make_render_observer(out);
    FrameObserver* observers[] = {observer.get()};
    run_session(*opt, observers);
  });
}

}  // namespace drumlab::cli
