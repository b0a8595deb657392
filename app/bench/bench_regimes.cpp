#include "app/bench/bench_regimes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <fmt/format.h>

#include "app/cli/scene_setup.hpp"
#include "engine/analysis/drum_observables.hpp"
#include "engine/analysis/flow_regime.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/simulation.hpp"
#include "engine/threads.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/xy_chart.hpp"
#endif

namespace drumlab::bench {

using cli::froude_number;
using cli::regime_for_froude;

namespace {

struct RegimeRow {
  double froude = 0.0;
  double omega = 0.0;
  double transient_s = 0.0;  ///< lift + settle, simulated s
  double window_s = 0.0;
  std::uint64_t steps = 0;
  std::string predicted;
  RegimeEvidence evidence;
  double flowing_layer = 0.0;  ///< mean over the window's samples, m
  double seconds = 0.0;        ///< wall clock
};

std::vector<double> default_froude(bool quick) {
  if (quick) return {1e-3, 1e-2, 0.1, 1.0};
  // 1e-4 ... 1 as asked, plus one point beyond each end of the map (slumping, centrifuging).
  return {3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0, 3.0};
}

RegimeWindow window_for(bool quick) {
  RegimeWindow w;
  if (quick) {
    w.lift_rad = 0.3;
    w.settle_rad = 0.05;
    w.settle_min_s = 0.1;
    w.window_rad = 0.3;
    w.window_min_s = 0.25;
    w.samples = 12;
  }
  return w;
}

/// The predicted regime string names the observed one ("rolling/cascading" agrees with both).
bool agrees(const std::string& predicted, std::string_view observed) {
  return observed != "unknown" && predicted.find(observed) != std::string::npos;
}

std::uint64_t steps_for(double seconds, double dt) {
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(seconds / dt)));
}

RegimeRow run_froude(const RollingState& settled, double fr, const RegimeWindow& w,
                     const ObservableOptions& observe) {
  RegimeRow row;
  row.froude = fr;
  SceneConfig scene = settled.scene;
  const double g = scene.gravity.norm() * std::cos(scene.drum.tilt);
  const double radius = 0.5 * scene.drum.diameter;
  row.omega = std::sqrt(fr * g / radius);
  const double lift_omega = std::max(row.omega, std::sqrt(w.lift_froude * g / radius));
  scene.drum.omega = row.omega;
  row.predicted = regime_for_froude(fr);  // the nominal Fr (endpoints sit on the boundaries)
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(scene, settled.state);
  const std::uint64_t lift = steps_for(w.lift_rad / lift_omega, sim.dt());
  const std::uint64_t settle =
      steps_for(std::max(w.settle_rad / row.omega, w.settle_min_s), sim.dt());
  row.window_s = std::max(w.window_rad / row.omega, w.window_min_s);
  const std::uint64_t between = steps_for(row.window_s / w.samples, sim.dt());
  sim.set_drum_omega(lift_omega);
  sim.advance(lift);
  sim.set_drum_omega(row.omega);
  sim.advance(settle);
  row.transient_s = static_cast<double>(lift + settle) * sim.dt();
  std::vector<DrumObservables> window;
  for (int s = 0; s < w.samples; ++s) {
    sim.advance(between);
    window.push_back(measure_drum(sim, observe));
    row.flowing_layer += window.back().flowing_layer_thickness / w.samples;
  }
  sim.check_stability();
  row.evidence = classify_regime(window);
  row.steps = lift + settle + between * static_cast<std::uint64_t>(w.samples);
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

/// Why an observed regime differs from the predicted one: the rule that decided, and whether Fr
/// lies within a factor of 3 of a boundary of the Mellmann map.
std::string disagreement(const RegimeRow& r) {
  std::string why = regime_reason(r.evidence);
  for (const double b : {1e-4, 1e-3, 1e-2, 0.1, 1.0}) {
    if (r.froude >= b / 3.0 && r.froude <= 3.0 * b) {
      why += fmt::format("; Fr within x3 of the map boundary {:g}", b);
      break;
    }
  }
  return why;
}

void print_row(const RegimeRow& r) {
  const RegimeEvidence& e = r.evidence;
  const std::string_view observed = regime_name(e.regime);
  fmt::print(
      "{:>7g} {:>7.3f} {:>6.2f} {:>6.2f} {:<18} {:<13} {:<5} {:>6.1f} {:>6.1f} {:>6.2f} "
      "{:>6.2f} {:>6.2f} {:>6.3f} {:>6.3f} {:>6.2f} {:>7.1f} {:>6.0f}\n",
      r.froude, r.omega, r.transient_s, r.window_s, r.predicted, observed,
      agrees(r.predicted, observed) ? "yes" : "no", e.profile_angle_deg, e.smoothed_swing_deg,
      e.still_share, e.intermittency, e.speed_ratio, e.curvature, e.airborne_fraction,
      e.upper_fraction, 1e3 * r.flowing_layer, r.seconds);
}

void write_csv(const std::filesystem::path& file, const std::string& scene,
               const std::vector<RegimeRow>& rows) {
  write_file_atomically(file, [&](std::ostream& os) {
    os << "scene,froude,omega,transient_s,window_s,steps,predicted,observed,agrees,"
          "angle_of_repose_deg,mean_sample_angle_deg,angle_swing_deg,smoothed_swing_deg,"
          "still_share,intermittency,speed_ratio,relative_speed,curvature,airborne_fraction,"
          "upper_fraction,com_offset,flowing_layer_m,wall_s\n";
    for (const RegimeRow& r : rows) {
      const RegimeEvidence& e = r.evidence;
      os << fmt::format(
          "{},{:g},{:.6g},{:.6g},{:.6g},{},{},{},{},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},"
          "{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.4g},{:.3g}\n",
          scene, r.froude, r.omega, r.transient_s, r.window_s, r.steps, r.predicted,
          regime_name(e.regime), agrees(r.predicted, regime_name(e.regime)) ? 1 : 0,
          e.profile_angle_deg, e.mean_angle_deg, e.angle_swing_deg, e.smoothed_swing_deg,
          e.still_share, e.intermittency, e.speed_ratio, e.relative_speed, e.curvature,
          e.airborne_fraction, e.upper_fraction, e.com_offset, r.flowing_layer, r.seconds);
    }
  });
}

void write_chart(const std::filesystem::path& file, const std::string& scene,
                 const std::vector<RegimeRow>& rows) {
#ifdef DRUMLAB_WITH_RENDER
  render::XYSeries profile{"window-mean surface", {}, {}, true};
  render::XYSeries sample_mean{"mean of the per-sample fits", {}, {}, false};
  render::XYSeries still{"still share", {}, {}, false};
  render::XYSeries air{"in flight x10", {}, {}, false};
  render::XYSeries curv{"surface curvature x10", {}, {}, false};
  render::XYSeries interm{"intermittency", {}, {}, false};
  for (const RegimeRow& r : rows) {
    const RegimeEvidence& e = r.evidence;
    for (auto* s : {&profile, &sample_mean, &still, &air, &curv, &interm}) {
      s->x.push_back(r.froude);
    }
    // A bed carried round has no free surface: no angle of repose drawn.
    const bool ring = e.regime == FlowRegime::centrifuging;
    profile.y.push_back(ring ? NAN : e.profile_angle_deg);
    sample_mean.y.push_back(ring ? NAN : e.mean_angle_deg);
    interm.y.push_back(e.intermittency);
    still.y.push_back(e.still_share);
    air.y.push_back(10.0 * e.airborne_fraction);
    curv.y.push_back(10.0 * e.curvature);
  }
  std::string observed;
  for (const RegimeRow& r : rows) {
    observed += fmt::format("{}{:g}: {}", observed.empty() ? "" : ", ", r.froude,
                            regime_name(r.evidence.regime));
  }
  render::XYPanel a{fmt::format("{}: dynamic angle of repose vs Froude number", scene),
                    "Froude number",
                    "degrees",
                    {profile, sample_mean},
                    true,
                    false};
  render::XYPanel b{"regime evidence (rules: engine/analysis/flow_regime.hpp)",
                    "Froude number",
                    "share",
                    {still, interm, air, curv},
                    true,
                    false};
  render::write_xy_charts({a, b}, file, 1800, 600);
  fmt::print("wrote {} (observed: {})\n", file.string(), observed);
#else
  (void)scene, (void)rows;
  fmt::print("note: built without rendering: no chart {}\n", file.string());
#endif
}

}  // namespace

void run_bench_regimes(const RegimesBenchOptions& opt) {
  const std::vector<double> froude = opt.froude.empty() ? default_froude(opt.quick) : opt.froude;
  for (const double fr : froude) {
    if (!(fr > 0.0) || !std::isfinite(fr)) {
      throw InputError(fmt::format("--froude {}: must be a positive number", fr));
    }
  }
  const std::filesystem::path out = opt.out;
  make_output_dir(out);
  set_thread_count(1);  // small drums: one thread; 2 threads on a busy 2-core VM crawl
  const auto t_start = std::chrono::steady_clock::now();
  RollingPlan plan = opt.plan;
  plan.turn_revolutions = 0.0;  // settled at rest; each Froude number turns it from there
  const RollingState settled = rolling_state(opt.scene, plan);
  const std::string& name = settled.scene.name;
  const RegimeWindow w = window_for(opt.quick);
  fmt::print("scene             {} ({}), {} particles\n", name, opt.scene,
             settled.state.particles.size());
  if (!settled.scene.description.empty()) {
    fmt::print("description       {}\n", settled.scene.description);
  }
  fmt::print("state             {} (bed settled with the drum at rest)\n", settled.origin);
  fmt::print(
      "window            per Fr: lift {} rad at max(Fr, {:g}), settle max({} rad, {} s) at Fr, "
      "then a window of max({} rad, {} s) with {} samples of the drum observables{}\n",
      w.lift_rad, w.lift_froude, w.settle_rad, w.settle_min_s, w.window_rad, w.window_min_s,
      w.samples, opt.quick ? " (--quick)" : "");
  fmt::print(
      "{:>7} {:>7} {:>6} {:>6} {:<18} {:<13} {:<5} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} "
      "{:>6} {:>7} {:>6}\n",
      "Fr", "omega", "trans", "window", "predicted (Fr)", "observed", "agree", "angle", "swing",
      "still", "interm", "flow", "curv", "air", "upper", "layermm", "wall_s");
  ObservableOptions observe;
  observe.column_width = opt.column_width;
  std::vector<RegimeRow> rows;
  for (const double fr : froude) {
    rows.push_back(run_froude(settled, fr, w, observe));
    print_row(rows.back());
    std::fflush(stdout);
  }
  fmt::print(
      "trans/window: simulated s (lift + settle / window); angle: dynamic angle of repose of the "
      "window-mean surface (deg); swing: max - min of the {}-sample moving average of the "
      "per-sample angle; still: share of samples moving at <= 1/4 of the window's mean speed "
      "relative to the drum; interm: std/mean of that speed (intermittency); flow: its mean / "
      "(omega R); curv: "
      "curvature of the window-mean surface; air: share of particles in flight; upper: share "
      "above the axis (rules: engine/analysis/flow_regime.hpp). Predicted: Mellmann (2001) "
      "Froude ranges.\n",
      FlowRegimeThresholds{}.smoothing);
  for (const RegimeRow& r : rows) {
    if (agrees(r.predicted, regime_name(r.evidence.regime))) continue;
    fmt::print("disagrees at Fr {:g}: predicted {}, observed {}: {}\n", r.froude, r.predicted,
               regime_name(r.evidence.regime), disagreement(r));
  }
  const auto csv = out / fmt::format("regimes_{}.csv", name);
  write_csv(csv, name, rows);
  fmt::print("wrote {}\n", csv.string());
  write_chart(out / fmt::format("regimes_{}.png", name), name, rows);
  fmt::print("total             {:.0f} s wall\n",
             std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count());
}

}  // namespace drumlab::bench
