#include "app/bench/bench_accuracy_cases.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

#include "engine/contact/hertz_mindlin.hpp"
#include "engine/simulation.hpp"

namespace drumlab::bench {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The scene's physics with the setting applied, without gravity or a turning drum.
SceneConfig bare_scene(const SceneConfig& scene, const RunSettings& s) {
  SceneConfig c = scene;
  c.gravity = Vec3::Zero();
  c.drum = DrumConfig{1.0, 1.0, 0.0, 0.0, DrumEnds::caps, {}};
  c.material.friction = 0.0;
  c.material.rolling_friction = 0.0;
  c.wall = c.material;
  c.search_method = s.method;
  c.performance = s.performance;
  c.time.dt.reset();
  c.time.dt_factor = s.dt_factor;
  c.output.diagnostics_every = 1000;
  return c;
}

double surface_overlap(const Particles& p) {
  return p.radius[0] + p.radius[1] - (p.position[0] - p.position[1]).norm();
}

/// Runs the collision; returns {restitution, duration} with contact start and end interpolated.
std::pair<double, double> collide(const SceneConfig& scene, double r) {
  Particles p;
  const double gap = 0.02 * r;
  p.add(Vec3(-r - 0.5 * gap, 0.0, 0.5), r, scene.material.density);
  p.add(Vec3(r + 0.5 * gap, 0.0, 0.5), r, scene.material.density);
  p.velocity[0] = Vec3(0.5 * kImpactSpeed, 0.0, 0.0);
  p.velocity[1] = Vec3(-0.5 * kImpactSpeed, 0.0, 0.0);
  // The sweep probes time steps beyond the safe limit on purpose (they may go unstable).
  Simulation sim(scene, std::move(p), SimulationOptions{.allow_unsafe_dt = true});
  double prev = surface_overlap(sim.particles());
  double t_start = -1.0;
  for (int k = 0; k < 1'000'000; ++k) {
    sim.step();
    const double ov = surface_overlap(sim.particles());
    const double t0 = sim.time() - sim.dt();
    if (t_start < 0.0 && ov > 0.0) t_start = t0 + sim.dt() * (-prev) / (ov - prev);
    if (t_start >= 0.0 && ov <= 0.0) {
      const Particles& q = sim.particles();
      return {(q.velocity[1].x() - q.velocity[0].x()) / kImpactSpeed,
              t0 + sim.dt() * prev / (prev - ov) - t_start};
    }
    prev = ov;
  }
  return {kNaN, kNaN};
}

double total_energy(const Diagnostics& d) {
  return d.kinetic_energy + d.rotational_energy + d.potential_energy + d.elastic_energy;
}

}  // namespace

CollisionResult binary_collision(const SceneConfig& scene, const RunSettings& s) {
  const double r = scene.min_radius();
  SceneConfig c = bare_scene(scene, s);
  CollisionResult out;
  try {
    out.restitution = collide(c, r).first;
    c.material.restitution = 1.0;
    c.wall = c.material;
    out.duration = collide(c, r).second;
  } catch (const UnstableError&) {
    out.restitution = out.duration = kNaN;
  }
  const double m = c.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double m_eff = 0.5 * m;
  const double r_eff = 0.5 * r;
  const double e_star = effective_youngs_modulus(c.material, c.material);
  out.hertz_duration =
      2.868 * std::pow(m_eff * m_eff / (r_eff * e_star * e_star * kImpactSpeed), 0.2);
  return out;
}

double energy_drift(const SceneConfig& scene, const RunSettings& s, double duration) {
  const double r = scene.min_radius();
  SceneConfig c = bare_scene(scene, s);
  c.gravity = Vec3(0.0, -9.81, 0.0);
  c.material.restitution = 1.0;
  c.wall = c.material;
  c.drum = DrumConfig{20.0 * r, 8.0 * r, 0.0, 0.0, DrumEnds::caps, {}};
  Particles p;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int ix = 0; ix < 6; ++ix) {
    for (int iy = 0; iy < 3; ++iy) {
      for (int iz = 0; iz < 2; ++iz) {
        const Index i = p.add(r * Vec3(-6.25 + 2.5 * ix, -6.0 + 2.5 * iy, 2.0 + 4.0 * iz), r,
                              c.material.density);
        p.velocity[i] = Vec3(u(rng), u(rng), u(rng));
      }
    }
  }
  try {
    Simulation sim(c, std::move(p), SimulationOptions{.allow_unsafe_dt = true});
    const Diagnostics d0 = sim.diagnostics();
    const double e0 = total_energy(d0);
    double e_ref = d0.kinetic_energy;
    for (std::size_t i = 0; i < sim.particles().size(); ++i) {
      e_ref += sim.particles().mass[i] * 9.81 * (sim.particles().position[i].y() + 10.0 * r);
    }
    const auto steps = static_cast<std::uint64_t>(std::ceil(duration / sim.dt()));
    const std::uint64_t block = std::max<std::uint64_t>(1, steps / 200);
    double drift = 0.0;
    for (std::uint64_t done = 0; done < steps; done += block) {
      sim.advance(std::min(block, steps - done));
      drift = std::max(drift, std::abs(total_energy(sim.diagnostics()) - e0) / e_ref);
    }
    return drift;
  } catch (const UnstableError&) {
    return kNaN;
  }
}

namespace {

DrumObservables average(const std::vector<DrumObservables>& v) {
  DrumObservables m;
  if (v.empty()) return m;
  const auto n = static_cast<double>(v.size());
  std::size_t with_surface = 0;
  for (const auto& o : v) {
    m.particles = o.particles;
    m.mean_kinetic_energy += o.mean_kinetic_energy / n;
    m.mean_rotational_energy += o.mean_rotational_energy / n;
    m.centre_of_mass += o.centre_of_mass / n;
    m.airborne_fraction += o.airborne_fraction / n;
    if (!o.surface_found) continue;
    ++with_surface;
    m.angle_of_repose_deg += o.angle_of_repose_deg;
    m.flowing_layer_thickness += o.flowing_layer_thickness;
    m.surface_curvature += o.surface_curvature;
  }
  m.surface_found = with_surface > 0;
  if (m.surface_found) {
    const auto ns = static_cast<double>(with_surface);
    m.angle_of_repose_deg /= ns;
    m.flowing_layer_thickness /= ns;
    m.surface_curvature /= ns;
  }
  return m;
}

}  // namespace

DrumRun run_drum(const RollingState& rolling, const RunSettings& s, double transient, double window,
                 int samples) {
  DrumRun run;
  SimulationState state = rolling.state;
  state.search_method = s.method;
  state.dt = s.dt_factor * rayleigh_time(rolling.scene.min_radius(), rolling.scene.material);
  SceneConfig scene = rolling.scene;
  scene.performance = s.performance;
  try {
    Simulation sim(scene, std::move(state));
    const auto t0 = sim.time();
    const auto timed = [&](std::uint64_t n) {
      const auto start = std::chrono::steady_clock::now();
      sim.advance(n);
      run.wall_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    timed(static_cast<std::uint64_t>(std::ceil(transient / sim.dt())));
    const auto per_sample = std::max<std::uint64_t>(
        1, static_cast<std::uint64_t>(std::ceil(window / samples / sim.dt())));
    for (int k = 0; k < samples; ++k) {
      timed(per_sample);
      run.samples.push_back(measure_drum(sim));
    }
    run.mean = average(run.samples);
    run.simulated_seconds = sim.time() - t0;
    run.steps = sim.steps() - rolling.state.steps;
    const Particles& p = sim.particles();
    run.final_position.assign(p.size(), Vec3::Zero());
    for (std::size_t i = 0; i < p.size(); ++i) run.final_position[p.id[i]] = p.position[i];
  } catch (const UnstableError& e) {
    run.failure = e.what();
  }
  return run;
}

SteadyCheck steady_check(const DrumRun& run) {
  SteadyCheck c;
  std::vector<double> a;
  for (const auto& o : run.samples) {
    if (o.surface_found) a.push_back(o.angle_of_repose_deg);
  }
  if (a.size() < 2) return c;
  const std::size_t h = a.size() / 2;
  double mean = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    (k < h ? c.first : c.second) += a[k];
    mean += a[k];
  }
  c.first /= static_cast<double>(h);
  c.second /= static_cast<double>(a.size() - h);
  mean /= static_cast<double>(a.size());
  double var = 0.0;
  for (const double v : a) var += (v - mean) * (v - mean);
  c.noise = std::sqrt(var / static_cast<double>(a.size() - 1) / static_cast<double>(a.size()));
  return c;
}

double drum_noise_floor(const DrumRun& run, double drum_radius) {
  const auto& v = run.samples;
  if (v.size() < 2) return kNaN;
  const auto n = static_cast<double>(v.size());
  const auto standard_error = [&](auto get) {
    double mean = 0.0;
    for (const auto& o : v) mean += get(o) / n;
    double var = 0.0;
    for (const auto& o : v) var += (get(o) - mean) * (get(o) - mean);
    return std::pair{std::sqrt(var / (n - 1.0) / n), mean};
  };
  double floor = 0.0;
  const auto add_relative = [&](auto get) {
    const auto [se, mean] = standard_error(get);
    if (mean != 0.0) floor = std::max(floor, se / std::abs(mean));
  };
  add_relative([](const DrumObservables& o) { return o.angle_of_repose_deg; });
  add_relative([](const DrumObservables& o) { return o.mean_kinetic_energy; });
  add_relative([](const DrumObservables& o) { return o.flowing_layer_thickness; });
  for (int axis = 0; axis < 3; ++axis) {
    const auto [se, mean] =
        standard_error([axis](const DrumObservables& o) { return o.centre_of_mass(axis); });
    (void)mean;
    floor = std::max(floor, se / drum_radius);
  }
  return floor;
}

}  // namespace drumlab::bench
