#include "app/bench/bench_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <fmt/format.h>

#include "app/bench/bench_accuracy_cases.hpp"
#include "app/cli/scene_setup.hpp"
#include "engine/analysis/flow_regime.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/simulation.hpp"
#include "engine/threads.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/xy_chart.hpp"
#endif

namespace drumlab::bench {

using cli::froude_number;
using cli::regime_for_froude;
using cli::shipped_scene;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// How long each drum run lasts and how the tiny cases run.
struct Protocol {
  double transient = 0.25;   ///< s after switching the setting, not measured
  double window = 0.75;      ///< s over which the observables are averaged
  int samples = 10;          ///< observables measured evenly over the window
  double energy_time = 1.0;  ///< s of the elastic frictionless system
};

/// One knob: its values (the first is the sweep's reference) and how a value sets RunSettings.
/// A new knob (Verlet skin, sort interval, ...) is one more row in sweep_table().
struct KnobSweep {
  std::string knob;
  std::string meaning;
  std::vector<std::string> values;
  void (*apply)(RunSettings&, const std::string&);
};

/// Every search method of the table (engine/search/search_methods.hpp) but verlet:mlgrid, whose
/// list is verlet's (the same pairs): nine runs.
std::vector<std::string> accuracy_search_methods() {
  std::vector<std::string> v = search_method_names();
  std::erase(v, "verlet:mlgrid");
  return v;
}

std::vector<KnobSweep> sweep_table(std::size_t particles) {
  std::vector<KnobSweep> t = {
      {"dt_factor",
       "time step / Rayleigh time (reference: the smallest)",
       {"0.02", "0.05", "0.1", "0.2", "0.4", "0.8"},
       [](RunSettings& s, const std::string& v) { s.dt_factor = std::stod(v); }},
      {"search", "contact search method (reference: brute, else the first)",
       accuracy_search_methods(), [](RunSettings& s, const std::string& v) { s.method = v; }},
      {"verlet_skin",
       "Verlet skin / R_min with verlet:m2 (reference: the first)",
       {"0.2", "0.5", "1.0"},
       [](RunSettings& s, const std::string& v) {
         s.method = "verlet:m2";
         s.performance.verlet_skin = std::stod(v);
       }},
      {"sort_every",
       "particle re-ordering interval, steps (reference: 0 = never)",
       {"0", "25", "100", "1000"},
       [](RunSettings& s, const std::string& v) { s.performance.sort_every = std::stoull(v); }},
  };
  if (particles > kAccuracyBruteMaxParticles) {
    auto& v = t[1].values;
    v.erase(std::remove(v.begin(), v.end(), "brute"), v.end());
  }
  return t;
}

struct Row {
  std::string knob;
  std::string value;
  RunSettings settings;
  CollisionResult collision;
  double drift = kNaN;
  DrumRun drum;
  double restitution_error = kNaN;
  double duration_error = kNaN;
  double angle_error = kNaN;
  double ke_error = kNaN;
  double layer_error = kNaN;
  double com_error = kNaN;
  double trajectory = kNaN;  ///< max displacement from the reference's final state / r_min

  double run_time() const {
    return drum.simulated_seconds > 0.0 ? drum.wall_seconds / drum.simulated_seconds : kNaN;
  }
  double drum_error() const { return std::max({angle_error, ke_error, layer_error, com_error}); }
};

double relative(double v, double ref) {
  if (!std::isfinite(v) || !std::isfinite(ref)) return kNaN;
  return ref != 0.0 ? std::abs(v - ref) / std::abs(ref) : std::abs(v - ref);
}

void compare(Row& row, const Row& ref, double drum_radius, double r_min, double e_set) {
  const CollisionResult& c = row.collision;
  row.restitution_error = relative(c.restitution, e_set);
  row.duration_error = relative(c.duration, c.hertz_duration);
  if (!row.drum.failure.empty() || !ref.drum.failure.empty()) return;
  const DrumObservables& a = row.drum.mean;
  const DrumObservables& b = ref.drum.mean;
  row.angle_error = relative(a.angle_of_repose_deg, b.angle_of_repose_deg);
  row.ke_error = relative(a.mean_kinetic_energy, b.mean_kinetic_energy);
  row.layer_error = relative(a.flowing_layer_thickness, b.flowing_layer_thickness);
  row.com_error = (a.centre_of_mass - b.centre_of_mass).norm() / drum_radius;
  double dev = 0.0;
  for (std::size_t i = 0; i < row.drum.final_position.size(); ++i) {
    dev = std::max(dev, (row.drum.final_position[i] - ref.drum.final_position[i]).norm());
  }
  row.trajectory = dev / r_min;
}

std::string num(double v, const char* unstable = "unstable") {
  return std::isfinite(v) ? fmt::format("{:.3g}", v) : std::string(unstable);
}

void print_header() {
  fmt::print("{:<10} {:<10} {:>9} {:>9} {:>9} {:>9} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}\n",
             "knob", "value", "wall/sim", "e_err", "tc_err", "E_drift", "angle", "angle_err",
             "KE_err", "layer_err", "COM_err", "drum_err", "traj/rmin");
}

void print_row(const Row& r) {
  fmt::print(
      "{:<10} {:<10} {:>9} {:>9} {:>9} {:>9} {:>8} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}\n", r.knob,
      r.value, num(r.run_time()), num(r.restitution_error), num(r.duration_error), num(r.drift),
      r.drum.failure.empty() ? fmt::format("{:.2f}", r.drum.mean.angle_of_repose_deg) : "unstable",
      num(r.angle_error, "-"), num(r.ke_error, "-"), num(r.layer_error, "-"), num(r.com_error, "-"),
      num(r.drum_error(), "-"), num(r.trajectory, "-"));
  std::fflush(stdout);
}

void write_csv(const std::filesystem::path& file, const std::string& scene,
               const std::vector<Row>& rows) {
  write_file_atomically(file, [&](std::ostream& os) {
    os << "scene,knob,value,dt_factor,method,steps,wall_s,simulated_s,wall_per_simulated_s,"
          "restitution,restitution_error,contact_duration_s,hertz_duration_s,duration_error,"
          "energy_drift,angle_deg,mean_ke_j,layer_m,com_x,com_y,com_z,angle_error,ke_error,"
          "layer_error,com_error,drum_error,trajectory_rmin,status\n";
    for (const Row& r : rows) {
      const DrumObservables& m = r.drum.mean;
      const bool ok = r.drum.failure.empty();
      os << fmt::format(
          "{},{},{},{},{},{},{:.6g},{:.6g},{},{:.8g},{},{:.6g},{:.6g},{},{},{},{},{},{},{},{},{},"
          "{},{},{},{},{},{}\n",
          scene, r.knob, r.value, r.settings.dt_factor, r.settings.method, r.drum.steps,
          r.drum.wall_seconds, r.drum.simulated_seconds, num(r.run_time(), ""),
          r.collision.restitution, num(r.restitution_error, ""), r.collision.duration,
          r.collision.hertz_duration, num(r.duration_error, ""), num(r.drift, ""),
          ok ? fmt::format("{:.6g}", m.angle_of_repose_deg) : "",
          ok ? fmt::format("{:.6g}", m.mean_kinetic_energy) : "",
          ok ? fmt::format("{:.6g}", m.flowing_layer_thickness) : "",
          ok ? fmt::format("{:.6g}", m.centre_of_mass.x()) : "",
          ok ? fmt::format("{:.6g}", m.centre_of_mass.y()) : "",
          ok ? fmt::format("{:.6g}", m.centre_of_mass.z()) : "", num(r.angle_error, ""),
          num(r.ke_error, ""), num(r.layer_error, ""), num(r.com_error, ""),
          num(r.drum_error(), ""), num(r.trajectory, ""), ok ? "ok" : "unstable");
    }
  });
}

#ifdef DRUMLAB_WITH_RENDER  // the chart marks the Pareto front
/// Orders rows by run time, rows without one (unstable runs) last.
bool by_run_time(const Row& a, const Row& b) {
  const double ta = std::isfinite(a.run_time()) ? a.run_time() : INFINITY;
  const double tb = std::isfinite(b.run_time()) ? b.run_time() : INFINITY;
  return ta < tb;
}

/// Indices of the rows on the Pareto front of (run time, error): sorted by run time, each has a
/// smaller error than every faster row. Rows without both figures (or with error 0) are left out.
std::vector<std::size_t> pareto_front(const std::vector<Row>& rows, double (*error)(const Row&)) {
  std::vector<std::size_t> idx;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double t = rows[k].run_time();
    const double e = error(rows[k]);
    if (std::isfinite(t) && std::isfinite(e) && e > 0.0) idx.push_back(k);
  }
  std::sort(idx.begin(), idx.end(),
            [&](std::size_t a, std::size_t b) { return by_run_time(rows[a], rows[b]); });
  std::vector<std::size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (const std::size_t k : idx) {
    if (error(rows[k]) < best) {
      best = error(rows[k]);
      front.push_back(k);
    }
  }
  return front;
}
#endif

struct ErrorMeasure {
  const char* title;
  double (*error)(const Row&);
};

const ErrorMeasure kMeasures[] = {
    {"restitution |e - e_set| / e_set", [](const Row& r) { return r.restitution_error; }},
    {"contact duration vs Hertz", [](const Row& r) { return r.duration_error; }},
    {"energy drift (elastic, mu = 0)", [](const Row& r) { return r.drift; }},
    {"drum observables (max rel.)", [](const Row& r) { return r.drum_error(); }},
};

void write_chart(const std::filesystem::path& file, const std::string& scene,
                 const std::vector<KnobSweep>& sweeps, const std::vector<Row>& rows,
                 double noise_floor) {
#ifdef DRUMLAB_WITH_RENDER
  std::vector<render::XYPanel> panels;
  for (const ErrorMeasure& m : kMeasures) {
    render::XYPanel p{
        fmt::format("{}: {}", scene, m.title), "wall s per simulated s", "error", {}, true, true};
    for (const KnobSweep& s : sweeps) {
      render::XYSeries series{s.knob, {}, {}, false};
      std::vector<const Row*> knob_rows;  // drawn in order of run time
      for (const Row& r : rows) {
        if (r.knob == s.knob) knob_rows.push_back(&r);
      }
      std::stable_sort(knob_rows.begin(), knob_rows.end(),
                       [](const Row* a, const Row* b) { return a->run_time() < b->run_time(); });
      for (const Row* r : knob_rows) {
        series.x.push_back(r->run_time());
        series.y.push_back(m.error(*r));
      }
      p.series.push_back(std::move(series));
    }
    if (m.error == kMeasures[3].error && std::isfinite(noise_floor)) {
      render::XYSeries noise{"noise floor (reference window)", {}, {}, false};
      for (const Row& r : rows) {
        if (!std::isfinite(r.run_time())) continue;
        noise.x.push_back(r.run_time());
        noise.y.push_back(noise_floor);
      }
      std::sort(noise.x.begin(), noise.x.end());
      p.series.push_back(std::move(noise));
    }
    render::XYSeries front{"Pareto front", {}, {}, true};
    for (const std::size_t k : pareto_front(rows, m.error)) {
      front.x.push_back(rows[k].run_time());
      front.y.push_back(m.error(rows[k]));
    }
    p.series.push_back(std::move(front));
    panels.push_back(std::move(p));
  }
  render::write_xy_charts(panels, file, 2000, 560);
  fmt::print("wrote {}\n", file.string());
#else
  (void)scene, (void)sweeps, (void)rows, (void)noise_floor;
  fmt::print("note: built without rendering: no chart {}\n", file.string());
#endif
}

/// Fastest row of a knob's sweep that meets `good`.
const Row* fastest(const std::vector<Row>& rows, const std::string& knob,
                   bool (*good)(const Row&)) {
  const Row* best = nullptr;
  for (const Row& r : rows) {
    if (r.knob != knob || !good(r) || !std::isfinite(r.run_time())) continue;
    if (best == nullptr || r.run_time() < best->run_time()) best = &r;
  }
  return best;
}

void print_recommendation(const std::vector<Row>& rows) {
  const Row* flow = fastest(rows, "dt_factor", [](const Row& r) {
    return r.restitution_error < 0.05 && r.duration_error < 0.05 && r.drum_error() < 0.05;
  });
  fmt::print(
      "recommended dt    drum flows: {} t_R (the fastest time step with collision errors < 5 % "
      "and drum observables within 5 % of the smallest-dt reference)\n",
      flow != nullptr ? flow->value : std::string("none"));
  const Row* exact = fastest(rows, "dt_factor", [](const Row& r) {
    return r.restitution_error < 0.02 && r.duration_error < 0.02 && r.drift < 1e-3;
  });
  fmt::print(
      "recommended dt    collisions and energy: {} t_R (the fastest with collision errors < 2 % "
      "and energy drift < 1e-3)\n",
      exact != nullptr ? exact->value : std::string("none"));
  const Row* search = fastest(rows, "search", [](const Row& r) { return r.drum_error() < 0.01; });
  if (search != nullptr) {
    fmt::print(
        "recommended search {}: the fastest method whose drum observables are within 1 % of the "
        "reference method's (trajectory deviation {} r_min)\n",
        search->value, num(search->trajectory));
  }
}

/// The setting printed before the sweep: scene, state, drum-run protocol, the analytic cases.
void print_setup(const AccuracyOptions& opt, const RollingState& rolling, const Protocol& pr) {
  const SceneConfig& scene = rolling.scene;
  const std::size_t n = rolling.state.particles.size();
  const double r_min = scene.min_radius();
  const double t_r = rayleigh_time(r_min, scene.material);
  fmt::print("scene             {} ({}), {} particles, Fr = {:.3g} ({} expected)\n", scene.name,
             opt.scene, n, froude_number(scene), regime_for_froude(froude_number(scene)));
  fmt::print("state             {}\n", rolling.origin);
  fmt::print(
      "drum runs         from that state: {} s transient, then a {} s window with {} samples "
      "(time averages); 1 thread; Rayleigh time {:.4g} s\n",
      pr.transient, pr.window, pr.samples, t_r);
  fmt::print(
      "collisions        two spheres r = {} m, {} m/s head-on; restitution against e = {}, "
      "elastic duration against Hertz\n",
      r_min, kImpactSpeed, scene.material.restitution);
  fmt::print("energy            36 elastic frictionless spheres r = {} m, {} s\n", r_min,
             pr.energy_time);
}

/// Every value of every knob: the analytic cases, the drum run, the errors against the sweep's
/// reference (its first value); each row printed as it is done.
std::vector<Row> run_sweeps(const std::vector<KnobSweep>& sweeps, const RunSettings& baseline,
                            const RollingState& rolling, const Protocol& pr) {
  const SceneConfig& scene = rolling.scene;
  const double r_min = scene.min_radius();
  const double drum_radius = 0.5 * scene.drum.diameter;
  print_header();
  std::vector<Row> rows;
  for (const KnobSweep& sweep : sweeps) {
    const std::size_t ref = rows.size();
    for (const std::string& value : sweep.values) {
      Row row{sweep.knob, value, baseline, {}, kNaN, {}};
      sweep.apply(row.settings, value);
      row.collision = binary_collision(scene, row.settings);
      row.drift = energy_drift(scene, row.settings, pr.energy_time);
      row.drum = run_drum(rolling, row.settings, pr.transient, pr.window, pr.samples);
      compare(row, rows.size() == ref ? row : rows[ref], drum_radius, r_min,
              scene.material.restitution);
      rows.push_back(std::move(row));
      print_row(rows.back());
    }
  }
  return rows;
}

/// What the columns mean, and the settings whose drum run went unstable.
void print_legend(const std::vector<Row>& rows) {
  fmt::print(
      "errors: e_err, tc_err relative to the exact values; E_drift max |E - E0| / E_ref; angle "
      "(deg), KE, layer relative and COM (/ drum radius) against the first value of the knob's "
      "sweep; drum_err the largest of those four; traj/rmin the largest particle displacement "
      "from that reference's final state / r_min; wall/sim: wall s per simulated s of the drum "
      "run\n");
  for (const Row& r : rows) {
    if (!r.drum.failure.empty())
      fmt::print("unstable          {} = {}: {}\n", r.knob, r.value, r.drum.failure);
  }
}

/// The reference drum run: its time averages, whether it is steady, the noise floor, the regime.
void print_reference(const Row& ref, const SceneConfig& scene) {
  const double drum_radius = 0.5 * scene.drum.diameter;
  const DrumObservables& m = ref.drum.mean;
  const SteadyCheck c = steady_check(ref.drum);
  fmt::print(
      "reference         {} = {}: angle {:.2f} deg, mean KE {:.4g} J, layer {:.4g} m, COM "
      "({:.4f}, {:.4f}, {:.4f}) m, curvature {:.3f}\n",
      ref.knob, ref.value, m.angle_of_repose_deg, m.mean_kinetic_energy, m.flowing_layer_thickness,
      m.centre_of_mass.x(), m.centre_of_mass.y(), m.centre_of_mass.z(), m.surface_curvature);
  fmt::print(
      "steady state      angle {:.2f} deg (first half of the window) vs {:.2f} deg (second "
      "half); standard error of the window mean {:.2f} deg ({:.2g} relative): drum errors "
      "below that are noise\n",
      c.first, c.second, c.noise,
      m.angle_of_repose_deg != 0.0 ? c.noise / std::abs(m.angle_of_repose_deg) : 0.0);
  fmt::print(
      "noise floor       {:.3g}: the largest relative standard error of a window mean (angle, "
      "KE, layer, COM / R) in the reference run; drum_err below it is not resolved\n",
      drum_noise_floor(ref.drum, drum_radius));
  std::string angles;
  for (const auto& o : ref.drum.samples) angles += fmt::format(" {:.1f}", o.angle_of_repose_deg);
  fmt::print("window angles    {} deg\n", angles);
  const RegimeEvidence regime = classify_regime(ref.drum.samples);
  fmt::print(
      "observed regime   {} (curvature {:.3f}, in flight {:.3f}, still share {:.2f}, angle swing "
      "{:.1f} deg; see engine/analysis/flow_regime.hpp); Fr predicts {}\n",
      regime_name(regime.regime), regime.curvature, regime.airborne_fraction, regime.still_share,
      regime.angle_swing_deg, regime_for_froude(froude_number(scene)));
}

}  // namespace

void run_bench_accuracy(AccuracyOptions opt) {
  if (opt.scene.empty()) {
    opt.scene = shipped_scene(opt.quick ? "accuracy_quick.toml" : "accuracy_drum.toml");
  }
  Protocol pr;
  if (opt.quick) pr = Protocol{0.05, 0.1, 5, 0.1};
  set_thread_count(1);  // run times comparable between settings and with bench throughput
  const std::filesystem::path out = opt.out;
  make_output_dir(out);
  const RollingState rolling = rolling_state(opt.scene, opt.plan);
  const SceneConfig& scene = rolling.scene;
  const double drum_radius = 0.5 * scene.drum.diameter;
  print_setup(opt, rolling, pr);
  const std::vector<KnobSweep> sweeps = sweep_table(rolling.state.particles.size());
  const RunSettings baseline{scene.time.dt_factor, scene.search_method, scene.performance};
  fmt::print("baseline          dt = {} t_R, search {} (knobs not swept keep these)\n",
             baseline.dt_factor, baseline.method);
  const std::vector<Row> rows = run_sweeps(sweeps, baseline, rolling, pr);
  print_legend(rows);
  const Row& ref = rows.front();
  if (ref.drum.failure.empty()) print_reference(ref, scene);
  print_recommendation(rows);
  const auto csv = out / fmt::format("accuracy_{}.csv", scene.name);
  write_csv(csv, scene.name, rows);
  fmt::print("wrote {}\n", csv.string());
  write_chart(out / fmt::format("accuracy_{}.png", scene.name), scene.name, sweeps, rows,
              ref.drum.failure.empty() ? drum_noise_floor(ref.drum, drum_radius) : kNaN);
}

}  // namespace drumlab::bench
