#include "app/cli/bench_regimes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <fmt/format.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "app/cli/scene_setup.hpp"
#include "engine/analysis/drum_observables.hpp"
#include "engine/analysis/flow_regime.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/simulation.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/bench_chart.hpp"
#endif

namespace drumlab::cli {

namespace {

struct RegimeRow {
  double froude = 0.0;
  double omega = 0.0;
  double transient_s = 0.0;
  double window_s = 0.0;
  std::uint64_t steps = 0;
  std::string predicted;
  RegimeEvidence evidence;
  double flowing_layer = 0.0;  ///< mean over the window's samples, m
  double seconds = 0.0;        ///< wall clock
};

std::vector<double> default_froude(bool quick) {
  if (quick) return {1e-3, 1e-2, 0.1, 1.0};
  return {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0};
}

RegimeWindow window_for(bool quick) {
  RegimeWindow w;
  if (quick) {
    w.transient_rad = 0.3;
    w.transient_min_s = 0.25;
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

RegimeRow run_froude(const RollingState& settled, double fr, const RegimeWindow& w,
                     const ObservableOptions& observe) {
  RegimeRow row;
  row.froude = fr;
  SceneConfig scene = settled.scene;
  const double g = scene.gravity.norm() * std::cos(scene.drum.tilt);
  row.omega = std::sqrt(fr * g / (0.5 * scene.drum.diameter));
  scene.drum.omega = row.omega;
  row.predicted = regime_for_froude(fr);  // the nominal Fr (endpoints sit on the boundaries)
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(scene, settled.state);
  sim.set_drum_omega(row.omega);
  row.transient_s = std::max(w.transient_rad / row.omega, w.transient_min_s);
  row.window_s = std::max(w.window_rad / row.omega, w.window_min_s);
  const auto transient = static_cast<std::uint64_t>(std::ceil(row.transient_s / sim.dt()));
  const auto between = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::ceil(row.window_s / sim.dt() / w.samples)));
  sim.advance(transient);
  std::vector<DrumObservables> window;
  for (int s = 0; s < w.samples; ++s) {
    sim.advance(between);
    window.push_back(measure_drum(sim, observe));
    row.flowing_layer += window.back().flowing_layer_thickness / w.samples;
  }
  row.evidence = classify_regime(window);
  row.steps = transient + between * static_cast<std::uint64_t>(w.samples);
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

void print_row(const RegimeRow& r) {
  const RegimeEvidence& e = r.evidence;
  const std::string_view observed = regime_name(e.regime);
  fmt::print(
      "{:>7g} {:>7.3f} {:>6.2f} {:>6.2f} {:<18} {:<13} {:<5} {:>6.1f} {:>6.1f} {:>6.2f} "
      "{:>6.3f} {:>6.3f} {:>6.2f} {:>7.1f} {:>6.0f}\n",
      r.froude, r.omega, r.transient_s, r.window_s, r.predicted, observed,
      agrees(r.predicted, observed) ? "yes" : "no", e.mean_angle_deg, e.angle_swing_deg,
      e.still_share, e.curvature, e.airborne_fraction, e.upper_fraction, 1e3 * r.flowing_layer,
      r.seconds);
}

void write_csv(const std::filesystem::path& file, const std::string& scene,
               const std::vector<RegimeRow>& rows) {
  write_file_atomically(file, [&](std::ostream& os) {
    os << "scene,froude,omega,transient_s,window_s,steps,predicted,observed,agrees,"
          "angle_of_repose_deg,angle_swing_deg,still_share,curvature,airborne_fraction,"
          "upper_fraction,com_offset,flowing_layer_m,wall_s\n";
    for (const RegimeRow& r : rows) {
      const RegimeEvidence& e = r.evidence;
      os << fmt::format(
          "{},{:g},{:.6g},{:.6g},{:.6g},{},{},{},{},{:.4g},{:.4g},{:.4g},{:.4g},"
          "{:.4g},{:.4g},{:.4g},{:.4g},{:.3g}\n",
          scene, r.froude, r.omega, r.transient_s, r.window_s, r.steps, r.predicted,
          regime_name(e.regime), agrees(r.predicted, regime_name(e.regime)) ? 1 : 0,
          e.mean_angle_deg, e.angle_swing_deg, e.still_share, e.curvature, e.airborne_fraction,
          e.upper_fraction, e.com_offset, r.flowing_layer, r.seconds);
    }
  });
}

void write_chart(const std::filesystem::path& file, const std::string& scene,
                 const std::vector<RegimeRow>& rows) {
#ifdef DRUMLAB_WITH_RENDER
  std::vector<std::string> labels;
  render::BarSeries angle{"dynamic angle of repose", {}}, layer{"flowing layer", {}};
  for (const RegimeRow& r : rows) {
    labels.push_back(fmt::format("{:g} {}", r.froude, regime_name(r.evidence.regime)));
    angle.values.push_back(r.evidence.mean_angle_deg);
    layer.values.push_back(1e3 * r.flowing_layer);
  }
  render::BarPanel a{fmt::format("{}: angle of repose vs Froude number (observed regime)", scene),
                     "degrees",
                     labels,
                     {angle},
                     false};
  render::BarPanel l{"flowing-layer thickness", "mm", labels, {layer}, false};
  render::write_bar_charts({a, l}, file);
  fmt::print("wrote {}\n", file.string());
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
#ifdef _OPENMP
  omp_set_num_threads(1);  // small drums: one thread; 2 threads on a busy 2-core VM crawl
#endif
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
      "window            per Fr: transient max({} rad of drum turn, {} s), then a window of "
      "max({} rad, {} s) with {} samples of the drum observables{}\n",
      w.transient_rad, w.transient_min_s, w.window_rad, w.window_min_s, w.samples,
      opt.quick ? " (--quick)" : "");
  fmt::print(
      "{:>7} {:>7} {:>6} {:>6} {:<18} {:<13} {:<5} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} "
      "{:>7} {:>6}\n",
      "Fr", "omega", "trans", "window", "predicted (Fr)", "observed", "agree", "angle", "swing",
      "still", "curv", "air", "upper", "layermm", "wall_s");
  ObservableOptions observe;
  observe.column_width = opt.column_width;
  std::vector<RegimeRow> rows;
  for (const double fr : froude) {
    rows.push_back(run_froude(settled, fr, w, observe));
    print_row(rows.back());
    std::fflush(stdout);
  }
  fmt::print(
      "trans/window: simulated s; angle: mean dynamic angle of repose (deg) over the window; "
      "swing: its max - min; still: share of samples without a flowing layer; curv: surface "
      "curvature; air: share of particles in flight; upper: share above the axis (see "
      "engine/analysis/flow_regime.hpp for the rules). Predicted: Mellmann (2001) Froude "
      "ranges.\n");
  const auto csv = out / fmt::format("regimes_{}.csv", name);
  write_csv(csv, name, rows);
  fmt::print("wrote {}\n", csv.string());
  write_chart(out / fmt::format("regimes_{}.png", name), name, rows);
}

}  // namespace drumlab::cli
