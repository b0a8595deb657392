// The in-process stress cases: drum flows that must stay stable with bounded energy, a conserved
// particle count and nobody outside the drum, and overlapping file packings that must be resolved
// gently.
#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "app/bench/stress_scene.hpp"
#include "app/bench/stress_suite.hpp"
#include "engine/session/run_session.hpp"
#include "engine/simulation.hpp"

namespace drumlab::bench {

namespace {

double total_mass(const Particles& p) {
  double m = 0.0;
  for (const double mi : p.mass) m += mi;
  return m;
}

double mechanical_energy(const Diagnostics& d) {
  return d.kinetic_energy + d.rotational_energy + d.elastic_energy;
}

/// True if the stable ids are still 0..N-1, each once.
bool ids_intact(const Particles& p) {
  std::vector<Index> ids(p.id.begin(), p.id.end());
  std::sort(ids.begin(), ids.end());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] != static_cast<Index>(i)) return false;
  }
  return true;
}

struct FlowPlan {
  double settle_time = 0.0;              ///< s with the drum at rest
  double turn_time = 0.0;                ///< s turning
  std::uint64_t min_particle_steps = 0;  ///< lengthen the turning phase to reach this
};

/// Runs `scene` from its fill and checks every `diagnostics_every` steps: finite, nobody
/// outside the drum, count and ids conserved, kinetic + rotational energy below a bound
/// 2 (E0 + 0.7 M ((omega R)^2 + 2 g D)): the initial mechanical energy plus, per unit mass, a
/// particle moving with the wall after falling the whole diameter (rolling adds 2/5).
StressOutcome run_flow(const SceneConfig& scene, const FlowPlan& plan) {
  try {
    SessionOptions options;
    options.settle_time = plan.settle_time;
    RunSession session(scene, options);  // the scene's fill, random or from a file
    const Simulation& sim = session.simulation();
    const std::size_t n0 = sim.particles().size();
    const Diagnostics d0 = sim.diagnostics();
    const double r_drum = 0.5 * scene.drum.diameter;
    const double v_wall = std::abs(scene.drum.omega) * r_drum;
    const double bound =
        2.0 * (mechanical_energy(d0) +
               0.7 * total_mass(sim.particles()) *
                   (v_wall * v_wall + 2.0 * scene.gravity.norm() * scene.drum.diameter));
    const std::uint64_t settle = session.settle_steps();
    auto turn = static_cast<std::uint64_t>(std::ceil(plan.turn_time / sim.dt()));
    if (plan.min_particle_steps > 0) {
      const std::uint64_t total = (plan.min_particle_steps + n0 - 1) / n0;
      turn = std::max(turn, total > settle ? total - settle : 0);
    }
    double ke_max = 0.0;
    double ke_turn_max = 0.0;  // turning phase only (the settling fall often dominates ke_max)
    double overlap_max = 0.0;
    std::string problem;
    // Checked after every chunk of output.diagnostics_every steps; a problem stops the run.
    const auto check = [&](bool turning) {
      return [&, turning](std::uint64_t, std::uint64_t) {
        const Diagnostics d = sim.diagnostics();
        ke_max = std::max(ke_max, d.kinetic_energy + d.rotational_energy);
        if (turning) ke_turn_max = std::max(ke_turn_max, d.kinetic_energy + d.rotational_energy);
        overlap_max = std::max(overlap_max, d.max_overlap_ratio);
        if (d.non_finite > 0) problem = fmt::format("{} non-finite", d.non_finite);
        if (d.outside_drum > 0) problem = fmt::format("{} outside the drum", d.outside_drum);
        if (sim.particles().size() != n0) problem = "particle count changed";
        if (!(ke_max <= bound)) problem = fmt::format("energy {:.3g} J above bound", ke_max);
        return problem.empty();
      };
    };
    session.settle(check(false));
    if (problem.empty()) session.advance(turn, check(true));
    if (problem.empty() && !ids_intact(sim.particles())) problem = "particle ids lost";
    // Mean particle speed against the wall speed at the end: ~1 when the bed turns with the drum.
    double mean_speed = 0.0;
    for (const Vec3& v : sim.particles().velocity) mean_speed += v.norm();
    mean_speed /= static_cast<double>(std::max<std::size_t>(1, n0));
    const std::string speed_ratio =
        v_wall > 0.0
            ? fmt::format("; mean speed / (omega R) {:.2g} at the end", mean_speed / v_wall)
            : "";
    const std::uint64_t steps = sim.steps();
    StressOutcome out;
    out.pass = problem.empty();
    out.observed = fmt::format(
        "{}; E_kin max {:.2g} J = {:.2g} % of bound (turning {:.2g} J); overlap max {:.2g} r; N "
        "{} -> {}; {} steps ({:.3g} particle-steps){}",
        out.pass ? "stable" : problem, ke_max, 100.0 * ke_max / bound, ke_turn_max, overlap_max, n0,
        sim.particles().size(), steps, static_cast<double>(steps) * static_cast<double>(n0),
        speed_ratio);
    return out;
  } catch (const UnstableError& e) {
    return {fmt::format("unstable: {}", e.what()), false};
  } catch (const InputError& e) {
    return {fmt::format("refused: {}", e.what()), false};
  }
}

SceneConfig write_and_load(const StressContext& ctx, const std::string& name,
                           const StressScene& s) {
  const auto file = write_text(ctx.work / (file_stem(name) + ".toml"), s.toml());
  return load_scene(file);
}

StressCase flow_case(const StressContext& ctx, std::string name, const StressScene& s,
                     FlowPlan plan, std::string expected = "") {
  StressCase c;
  c.setup =
      fmt::format("{}; settle {:g} s, turn {:g} s", s.summary(), plan.settle_time, plan.turn_time);
  c.expected = expected.empty() ? "stable, E_kin bounded, N conserved, nobody outside the drum"
                                : std::move(expected);
  c.run = [ctx, name, s, plan] {
    const SceneConfig scene = write_and_load(ctx, name, s);
    return run_flow(scene, plan);
  };
  c.name = std::move(name);
  return c;
}

/// Overlapping file packing in zero gravity, drum at rest: the stored elastic energy E0 may only
/// decrease (damped contacts; 1 % for the integrator's fluctuation), and no particle may move
/// faster than sqrt(2 E0 / m) (all of E0 in one particle).
StressCase gentle_release_case(const StressContext& ctx, bool quick) {
  StressScene s;
  s.zero_gravity = true;
  s.froude = 0.0;
  s.fill_file = "overlap_8pct_zero_g.csv";
  s.settle_time = 0.0;
  const std::size_t max_count = quick ? 120 : 400;
  StressCase c;
  c.name = "overlap 8% released";
  c.setup = fmt::format("lattice <= {} p, r 4 mm, overlap 0.08 r, g = 0, drum at rest, 0.05 s",
                        max_count);
  c.expected = "energy never above E0, speeds <= sqrt(2 E0 / m), stable";
  c.run = [ctx, s, max_count] {
    write_text(ctx.work / s.fill_file, lattice_csv(s, 0.004, 0.08, max_count));
    try {
      const SceneConfig scene = write_and_load(ctx, "overlap_release", s);
      RunSession session(scene, SessionOptions{});
      Simulation& sim = session.simulation();
      const double e0 = mechanical_energy(sim.diagnostics());
      const double m_min =
          *std::min_element(sim.particles().mass.begin(), sim.particles().mass.end());
      const double v_bound = std::sqrt(2.0 * e0 / m_min);
      const auto steps = static_cast<std::uint64_t>(std::ceil(0.05 / sim.dt()));
      double e_max = 0.0;
      double v_max = 0.0;
      for (std::uint64_t done = 0; done < steps; done += 10) {
        session.advance(10);
        e_max = std::max(e_max, mechanical_energy(sim.diagnostics()));
        for (const Vec3& v : sim.particles().velocity) v_max = std::max(v_max, v.norm());
      }
      const bool pass = e0 > 0.0 && e_max <= 1.01 * e0 && v_max <= v_bound;
      return StressOutcome{
          fmt::format("{} p, E0 {:.3g} J, E max {:.4g} E0, v max {:.3g} m/s (bound {:.3g}), "
                      "final E {:.2g} E0",
                      sim.particles().size(), e0, e_max / e0, v_max, v_bound,
                      mechanical_energy(sim.diagnostics()) / e0),
          pass};
    } catch (const std::exception& e) {
      return StressOutcome{fmt::format("error: {}", e.what()), false};
    }
  };
  return c;
}

/// Drum flows over the regime map: Fr = 1e-4 ... 3.
void add_regime_map_cases(const StressContext& ctx, const FlowPlan& plan,
                          std::vector<StressCase>& cases) {
  for (const double fr : {1e-4, 1e-2, 0.3, 1.0, 3.0}) {
    StressScene s;
    s.froude = fr;
    cases.push_back(flow_case(ctx, fmt::format("Fr {:g}", fr), s, plan));
  }
}

/// Two size classes, radius ratios 3 and 10.
void add_size_ratio_cases(const StressContext& ctx, const FlowPlan& plan,
                          std::vector<StressCase>& cases) {
  const bool quick = ctx.quick;
  {
    StressScene s;
    s.radius = 0.003;
    s.large_radius = 0.009;
    s.count = 300;
    cases.push_back(flow_case(ctx, "size ratio 3", s, plan));
  }
  {
    StressScene s;
    s.diameter = 0.15;
    s.depth = 0.04;
    s.radius = 0.0015;
    s.large_radius = 0.015;
    s.large_fraction = 0.8;
    s.count = quick ? 250 : 400;
    s.search = "mlgrid";  // m5 (cells of R_max, ~100 small particles each) was 1.6x slower here
    cases.push_back(flow_case(ctx, "size ratio 10", s, plan));
  }
}

/// Soft and stiff materials, no and high friction, periodic ends on a tilted drum.
void add_material_cases(const StressContext& ctx, const FlowPlan& plan,
                        std::vector<StressCase>& cases) {
  const bool quick = ctx.quick;
  {
    StressScene s;
    s.youngs_modulus = 1e5;
    cases.push_back(flow_case(ctx, "very soft (E 1e5)", s, plan));
  }
  {
    StressScene s;
    s.youngs_modulus = 1e10;
    s.count = quick ? 100 : 200;
    cases.push_back(
        flow_case(ctx, "very stiff (E 1e10)", s, {quick ? 0.01 : 0.05, quick ? 0.015 : 0.05, 0}));
  }
  {
    StressScene s;
    s.friction = 0.0;
    cases.push_back(flow_case(ctx, "zero friction", s, plan));
  }
  {
    StressScene s;
    s.friction = 1.5;
    s.rolling_friction = 0.2;
    cases.push_back(flow_case(ctx, "high friction", s, plan));
  }
  {
    StressScene s;
    s.periodic = true;
    s.tilt_deg = 20.0;
    cases.push_back(flow_case(ctx, "periodic ends, tilt 20 deg", s, plan));
  }
}

/// A file packing whose neighbours overlap by 8 % of the radius, in a turning drum.
StressCase overlap_in_drum_case(const StressContext& ctx, const FlowPlan& plan) {
  const bool quick = ctx.quick;
  StressScene s;
  s.fill_file = "overlap_8pct.csv";
  s.settle_time = 0.0;
  const std::size_t max_count = quick ? 150 : 400;
  StressCase c = flow_case(ctx, "overlap 8% in drum", s, {0.0, plan.turn_time, 0});
  c.setup = fmt::format("lattice <= {} p, r 4 mm, overlap 0.08 r, Fr 0.05, turn {:g} s", max_count,
                        plan.turn_time);
  auto inner = c.run;
  c.run = [ctx, s, max_count, inner] {
    write_text(ctx.work / s.fill_file, lattice_csv(s, 0.004, 0.08, max_count));
    return inner();
  };
  return c;
}

/// The full suite's long run: at least 1e8 particle-steps.
StressCase long_run_case(const StressContext& ctx) {
  StressScene s;
  s.diameter = 0.2;
  s.depth = 0.04;
  s.count = 1000;
  s.froude = 0.05;
  StressCase c = flow_case(ctx, "long run", s, {0.3, 0.0, 100'000'000},
                           "stable for >= 1e8 particle-steps, E_kin bounded, N conserved");
  c.setup = fmt::format("{}; >= 1e8 particle-steps", s.summary());
  return c;
}

}  // namespace

std::vector<StressCase> physics_stress_cases(const StressContext& ctx) {
  const bool quick = ctx.quick;
  const FlowPlan plan{quick ? 0.08 : 0.2, quick ? 0.12 : 1.0, 0};
  std::vector<StressCase> cases;
  add_regime_map_cases(ctx, plan, cases);
  add_size_ratio_cases(ctx, plan, cases);
  add_material_cases(ctx, plan, cases);
  cases.push_back(overlap_in_drum_case(ctx, plan));
  cases.push_back(gentle_release_case(ctx, quick));
  if (!quick) cases.push_back(long_run_case(ctx));
  return cases;
}

}  // namespace drumlab::bench
