#include "app/run/run_report.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <fmt/format.h>

#include "engine/openmp_waiting.hpp"
#include "engine/threads.hpp"

namespace drumlab::cli {

ProgressBar::ProgressBar(std::string label, std::uint64_t total_steps, bool shown)
    : label_(std::move(label)),
      total_(total_steps),
      tty_(shown && ::isatty(::fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(std::uint64_t done) {
  if (!tty_ || total_ == 0) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
  const int width = 30;
  const int filled =
      static_cast<int>(width * static_cast<double>(done) / static_cast<double>(total_));
  fmt::print(stderr, "\r{:<8} [{:<{}}] {:5.1f}%  {:8.0f} steps/s  ETA {:4.0f} s ", label_,
             std::string(static_cast<std::size_t>(filled), '='), width,
             100.0 * static_cast<double>(done) / static_cast<double>(total_), rate, eta);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (tty_ && total_ > 0) fmt::print(stderr, "\n");
}

void print_auto_choice(const SearchChoice& choice) {
  fmt::print("search auto       -> {}: {}\n", choice.method, choice.reason);
}

void print_session_choices(const RunSession& session) {
  if (const auto& r = session.restart()) {
    if (r->checkpoint_scene != session.scene().name) {
      fmt::print("note: {} was written by scene '{}', continuing with scene '{}'\n", r->file,
                 r->checkpoint_scene, session.scene().name);
    }
    if (r->dt_factor_ignored)
      fmt::print("note: --restart keeps the checkpoint's dt; --dt-factor ignored\n");
  }
  if (const auto& choice = session.auto_choice()) print_auto_choice(*choice);
  if (const auto& r = session.restart()) {
    const Simulation& sim = session.simulation();
    fmt::print("restart           {} (step {}, t = {:.6g} s)\n", r->file, sim.steps(), sim.time());
  }
}

RunSummary run_summary(const Simulation& sim, const PhaseStats& phase, std::uint64_t particles) {
  RunSummary s;
  s.particles = particles;
  s.phase = phase;
  s.dt = sim.dt();
  s.rayleigh_time = sim.rayleigh_time();
  s.time = sim.time();
  s.method = sim.search().name();
  s.method_description = sim.search().description();
  s.search_detail = sim.search().report();
  s.diagnostics = sim.diagnostics();
  if (const DropletCloud* spray = sim.spray()) s.spray = spray->totals();
  if (sim.scene().drum.orbit.active()) {
    s.carrier_field = (sim.body_acceleration() - sim.gravity()).norm();
    const double g = sim.gravity().norm();
    s.carrier_field_in_g = g > 0.0 ? *s.carrier_field / g : 0.0;
  }
  return s;
}

void print_summary(const RunSummary& s) {
  const PhaseStats& phase = s.phase;
  const double n = static_cast<double>(s.particles);
  const double steps = static_cast<double>(std::max<std::uint64_t>(phase.steps, 1));
  const double particle_steps = n * static_cast<double>(phase.steps);
  const double total = std::max(phase.timers.total(), 1e-12);
  const Diagnostics& d = s.diagnostics;
  auto share = [&](double t) { return 100.0 * t / total; };
  fmt::print("particles         {}\n", s.particles);
  fmt::print(
      "steps             {} (dt = {:.4g} s = {:.3g} Rayleigh times), simulated {:.4g} s, t = "
      "{:.4g} s\n",
      phase.steps, s.dt, s.dt / s.rayleigh_time, static_cast<double>(phase.steps) * s.dt, s.time);
  fmt::print("search method     {} ({})\n", s.method, s.method_description);
#ifdef _OPENMP
  fmt::print("threads           {} (OpenMP: pair forces, walls, integration); waiting: {}\n",
             max_threads(), openmp_waiting_description());
#endif
  const double stepping = phase.wall_seconds - phase.output_seconds;
  fmt::print("wall time         {:.3f} s (stepping {:.3f} s, output {:.3f} s)\n",
             phase.wall_seconds, stepping, phase.output_seconds);
  fmt::print("throughput        {:.4g} particle-steps/s (stepping only)\n",
             stepping > 0 ? particle_steps / stepping : 0.0);
  fmt::print(
      "time split        search {:.1f} %, forces {:.1f} %, walls {:.1f} %, integration {:.1f} %, "
      "re-ordering {:.1f} %\n",
      share(phase.timers.search), share(phase.timers.forces), share(phase.timers.walls),
      share(phase.timers.integration), share(phase.timers.reorder));
  if (s.spray) {
    fmt::print(
        "spray pass        {:.3f} s = {:.2f} % of the step (the droplets' flight and absorption)\n",
        phase.timers.spray, share(phase.timers.spray));
  }
  fmt::print(
      "search / particle cells visited {:.2f}, pairs tested {:.2f}, contacts {:.3f}, tested per "
      "contact {:.2f}\n",
      static_cast<double>(phase.search.cells_visited) / (n * steps),
      static_cast<double>(phase.search.pairs_tested) / (n * steps),
      2.0 * static_cast<double>(phase.search.pairs_found) / (n * steps),
      phase.search.pairs_found > 0 ? static_cast<double>(phase.search.pairs_tested) /
                                         static_cast<double>(phase.search.pairs_found)
                                   : 0.0);
  if (!s.search_detail.empty()) fmt::print("search detail     {}\n", s.search_detail);
  fmt::print(
      "energy            kinetic {:.5g} J, rotational {:.5g} J, potential {:.5g} J, elastic {:.5g} "
      "J\n",
      d.kinetic_energy, d.rotational_energy, d.potential_energy, d.elastic_energy);
  if (s.carrier_field) {
    fmt::print(
        "carrier           field {:.4g} m/s^2 = {:.3g} g; kinetic energy in the lab frame {:.5g} J "
        "(above: in the frame that moves with the drum's centre)\n",
        *s.carrier_field, s.carrier_field_in_g, d.lab_kinetic_energy);
  }
  fmt::print(
      "health            max overlap/radius {:.4f}, outside drum {}, non-finite {}, contacts {} + "
      "{} wall\n",
      d.max_overlap_ratio, d.outside_drum, d.non_finite, d.contacts, d.wall_contacts);
  if (s.spray) {
    const SprayTotals& t = *s.spray;
    fmt::print(
        "spray             sprayed {:.6g} m^3 in {} droplets = airborne {:.6g} + absorbed by "
        "particles {:.6g} ({} droplets) + lost at the wall {:.6g} ({} droplets)",
        t.sprayed, t.emitted_count, t.airborne, t.absorbed, t.absorbed_count, t.lost, t.lost_count);
    if (t.walled_count > 0) {
      fmt::print(" + wetting the wall {:.6g} ({} droplets; {:.6g} of it taken up by particles)",
                 t.walled, t.walled_count, t.taken_from_wall);
    }
    fmt::print("\n");
    if (t.walled_count > 0) fmt::print("wall film         {:.12g} m^3 on the wall\n", t.on_wall);
    fmt::print("liquid            films + bridges + wall bridges {:.12g} m^3\n", d.liquid_volume);
  }
}

void settle_with_progress(RunSession& session, std::uint64_t steps, bool shown) {
  if (steps == 0) return;
  ProgressBar bar("settle", steps, shown);
  session.settle([&](std::uint64_t done, std::uint64_t) {
    bar.update(done);
    return true;
  });
  bar.finish();
}

TurnResult settle_and_turn(RunSession& session, std::uint64_t every,
                           std::span<FrameObserver* const> observers, bool print) {
  const Simulation& sim = session.simulation();
  const SessionPlan plan = session.plan();
  if (print) {
    fmt::print("scene             {} ({})\n", session.scene().name, session.options().scene_file);
    fmt::print(
        "plan              settle {} steps ({:.3g} s, drum at rest), then turn {} steps ({:.3g} "
        "s, {:.3g} rev)\n",
        plan.settle_steps, plan.settle_time, plan.turn_steps,
        static_cast<double>(plan.turn_steps) * sim.dt(),
        static_cast<double>(plan.turn_steps) * sim.dt() * std::abs(session.scene().drum.omega) /
            (2.0 * std::numbers::pi));
  }
  settle_with_progress(session, plan.settle_steps, print);
  ProgressBar bar("turn", plan.turn_steps, print);
  const TurnResult turn =
      session.run_turn(plan.turn_steps, every, observers, [&](std::uint64_t done, std::uint64_t) {
        bar.update(done);
        return true;
      });
  bar.finish();
  if (print) fmt::print("-- turning phase --\n");
  return turn;
}

void print_team(const RunSession& session) {
  if (const TeamChooser* t = session.team_chooser()) {
    fmt::print(
        "team              {} (settling and turning; the faster team runs; `--team fixed`: always "
        "{})\n",
        team_report(*t), t->threads());
  }
}

}  // namespace drumlab::cli
