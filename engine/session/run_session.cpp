#include "engine/session/run_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "engine/fill/file_fill.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/restart_check.hpp"
#include "engine/threads.hpp"

namespace drumlab {

SceneConfig load_dynamic_scene(const std::string& file) {
  SceneConfig scene = load_scene(file);
  if (!scene.dynamic()) {
    throw InputError(fmt::format(
        "{}: fill.kind: 'paper_packing' is a static packing for `drumlab paper-table`, not a "
        "dynamic run",
        file));
  }
  return scene;
}

std::optional<SearchChoice> resolve_auto_search(SceneConfig& scene, const Particles& particles,
                                                double dt) {
  if (scene.search_method != "auto") return std::nullopt;
  SearchChoice choice = choose_search_method(scene, dt, particles.position, particles.radius);
  scene.search_method = choice.method;
  return choice;
}

namespace {

/// The time step a fresh run will take (the scene's dt, or its dt factor of the Rayleigh time).
double planned_dt(const SceneConfig& scene, double dt_factor) {
  return scene.time.dt.value_or((dt_factor > 0.0 ? dt_factor : scene.time.dt_factor) *
                                rayleigh_time(scene.min_radius(), scene.material));
}

}  // namespace

SceneConfig scene_with_options(SceneConfig scene, const SessionOptions& options) {
  if (!options.method.empty()) scene.search_method = options.method;
  if (options.sort_every >= 0) {
    scene.performance.sort_every = static_cast<std::uint64_t>(options.sort_every);
  }
  if (options.skin > 0.0) scene.performance.verlet_skin = options.skin;
  return scene;
}

RunSession::RunSession(SceneConfig scene, SessionOptions options)
    : scene_(scene_with_options(std::move(scene), options)), options_(std::move(options)) {
  if (options_.restart.empty()) {
    SimulationOptions sim_options;
    sim_options.allow_unsafe_dt = options_.unsafe_dt;
    sim_options.dt_factor_override = options_.dt_factor;
    Particles particles = initial_fill(scene_);
    auto_choice_ = resolve_auto_search(scene_, particles, planned_dt(scene_, options_.dt_factor));
    sim_ = std::make_unique<Simulation>(scene_, std::move(particles), sim_options);
    return;
  }
  Checkpoint c = read_checkpoint(options_.restart);
  check_restart_count(scene_, c.particles, options_.restart);
  check_restart_particles(scene_, c.state.particles, options_.restart);
  restart_ = RestartInfo{options_.restart, c.scene_name, options_.dt_factor > 0.0};
  if (!options_.method.empty()) {
    auto_choice_ = resolve_auto_search(scene_, c.state.particles, c.state.dt);
  }
  const std::string method = scene_.search_method;
  try {
    sim_ = std::make_unique<Simulation>(scene_, std::move(c.state));
  } catch (const InputError& e) {  // "restart state: ...": say which file holds that state
    throw InputError(fmt::format("{}: {}", options_.restart, e.what()));
  }
  if (!options_.method.empty()) sim_->set_search_method(method);
}

RunSession::RunSession(SceneConfig scene, SessionOptions options, std::unique_ptr<Simulation> sim,
                       std::optional<RestartInfo> restart, std::optional<SearchChoice> auto_choice)
    : scene_(std::move(scene)),
      options_(std::move(options)),
      sim_(std::move(sim)),
      auto_choice_(std::move(auto_choice)),
      restart_(std::move(restart)) {}

std::uint64_t RunSession::settle_steps() const {
  if (restart_) return 0;
  const double t = options_.settle_time >= 0.0 ? options_.settle_time : scene_.fill.settle_time;
  return static_cast<std::uint64_t>(std::ceil(t / sim_->dt()));
}

SessionPlan session_plan(const SceneConfig& scene, const SessionOptions& options, double dt,
                         bool restart) {
  SessionPlan p;
  p.settle_time = restart                      ? 0.0
                  : options.settle_time >= 0.0 ? options.settle_time
                                               : scene.fill.settle_time;
  p.settle_steps = restart ? 0 : static_cast<std::uint64_t>(std::ceil(p.settle_time / dt));
  if (options.steps) {  // 0 too: fill and settle only, as LAMMPS's `run 0`
    p.turn_steps = *options.steps;
    return p;
  }
  const double omega = std::abs(scene.drum.omega);
  double seconds = 0.0;
  if (options.revolutions > 0.0 || scene.time.revolutions) {
    const double revs = options.revolutions > 0.0 ? options.revolutions : *scene.time.revolutions;
    if (omega == 0.0) {
      throw InputError(
          fmt::format("{}: drum.omega: revolutions need a turning drum", options.scene_file));
    }
    seconds = revs * 2.0 * std::numbers::pi / omega;
  } else if (scene.time.duration) {
    seconds = *scene.time.duration;
  } else {
    throw InputError(fmt::format(
        "{}: time: set duration or revolutions in the scene, or pass --steps/--revolutions",
        options.scene_file));
  }
  p.turn_steps = static_cast<std::uint64_t>(std::ceil(seconds / dt));
  return p;
}

SessionPlan RunSession::plan() const {
  return session_plan(scene_, options_, sim_->dt(), restart_.has_value());
}

std::uint64_t RunSession::advance_chunked(std::uint64_t n, std::span<const std::uint64_t> every,
                                          const std::function<void(std::uint64_t)>& after_chunk,
                                          const SessionProgress& progress) {
  const std::uint64_t chunk = std::max<std::uint64_t>(1, sim_->scene().output.diagnostics_every);
  if (options_.adaptive_team && !team_ && max_threads() > 1)
    team_.emplace(max_threads(), options_.team_probe_every);
  std::uint64_t done = 0;
  while (done < n) {
    std::uint64_t k = std::min(chunk, n - done);
    for (const std::uint64_t e : every) {
      if (e > 0) k = std::min(k, e - done % e);
    }
    if (team_) {  // a window of steps with the chosen team, timed
      k = std::min(k, TeamChooser::kWindowSteps);
      set_thread_count(team_->team());
      const auto t0 = std::chrono::steady_clock::now();
      sim_->advance(k);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      set_thread_count(team_->threads());
      team_->record(seconds, k);
    } else {
      sim_->advance(k);
    }
    done += k;
    if (after_chunk) after_chunk(done);
    if (progress && !progress(done, n)) break;
  }
  return done;
}

void RunSession::settle(const SessionProgress& progress) {
  const std::uint64_t steps = settle_steps();
  if (steps == 0) return;
  // The drum and a planetary carrier stand while the bed settles.
  sim_->set_drum_omega(0.0);
  sim_->set_carrier_running(false);
  advance_chunked(steps, {}, {}, progress);
  sim_->set_drum_omega(scene_.drum.omega);
  sim_->set_carrier_running(true);
}

std::uint64_t RunSession::advance(std::uint64_t n, const SessionProgress& progress) {
  return advance_chunked(n, {}, {}, progress);
}

TurnResult RunSession::run_turn(std::uint64_t steps, std::uint64_t every,
                                std::span<FrameObserver* const> observers,
                                const SessionProgress& progress) {
  TurnResult r;
  const PhaseMeter meter(*sim_);
  double output_seconds = 0.0;
  // Each observer's schedule; `every` itself too, whose frames are checked for stability also
  // when no observer takes them.
  std::vector<std::uint64_t> cadence{every};
  for (const FrameObserver* o : observers) cadence.push_back(o->every() > 0 ? o->every() : every);
  std::vector<std::uint64_t> frames(observers.size(), 0);
  const auto due = [&](std::size_t k, std::uint64_t done) {
    return cadence[k] > 0 && done % cadence[k] == 0;
  };
  const auto emit = [&](std::uint64_t done) {
    bool any = false;
    for (std::size_t k = 0; k < cadence.size(); ++k) any = any || due(k, done);
    if (!any) return;
    // No frame of a bad state: a writer sees only a state that has just passed the stability
    // check (finite, inside the drum, sane overlaps), also for frame 0 of a restart.
    sim_->check_stability();
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < observers.size(); ++k) {
      if (due(k + 1, done)) observers[k]->on_frame(*sim_, frames[k]++);
    }
    ++r.frames;
    output_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  emit(0);
  r.stopped = advance_chunked(steps, cadence, emit, progress) < steps;
  r.stats = meter.finish();
  r.stats.output_seconds = output_seconds;
  for (FrameObserver* o : observers) o->on_finish(*sim_);
  return r;
}

void RunSession::set_search_method(const std::string& name) {
  std::string method = name;
  if (name == "auto") {
    SceneConfig probe = scene_;
    probe.search_method = "auto";
    auto_choice_ = resolve_auto_search(probe, sim_->particles(), sim_->dt());
    method = probe.search_method;
  }
  sim_->set_search_method(method);
  scene_.search_method = method;
}

}  // namespace drumlab
