#pragma once
// The measurements behind `drumlab bench accuracy`: each runs one setting of the engine's knobs on
// a case with an exact or reference answer. See bench_accuracy.hpp for the sweep.
#include <string>
#include <vector>

#include "app/bench/bench_state.hpp"
#include "engine/analysis/drum_observables.hpp"

namespace drumlab::bench {

/// One point in knob space: everything a sweep may change.
struct RunSettings {
  double dt_factor = 0.2;         ///< time step / Rayleigh time of the smallest particle
  std::string method;             ///< contact search method
  PerformanceConfig performance;  ///< Verlet skin, particle sort interval
};

/// Head-on collision of two equal spheres (the scene's smallest radius and material).
struct CollisionResult {
  double restitution = 0.0;  ///< achieved, with the scene's restitution (exact answer: that value)
  double duration = 0.0;     ///< s, elastic (e = 1) contact duration
  double hertz_duration = 0.0;  ///< s, 2.868 (m*^2 / (R* E*^2 v))^(1/5)
};
inline constexpr double kImpactSpeed = 1.0;  ///< m/s, relative speed of the binary collisions

CollisionResult binary_collision(const SceneConfig& scene, const RunSettings& s);

/// Largest |E(t) - E(0)| / E_ref over `duration` s of 36 elastic frictionless spheres (the
/// scene's smallest radius and material, e = 1, mu = 0) bouncing in a closed drum of 20 radii
/// under gravity (E_ref: kinetic + potential above the drum bottom at t = 0). NaN if it went
/// unstable.
double energy_drift(const SceneConfig& scene, const RunSettings& s, double duration);

/// Drum observables of a steady rolling state run with one setting.
struct DrumRun {
  std::vector<DrumObservables> samples;  ///< evenly spaced over the window
  DrumObservables mean;                  ///< time average of the samples (scalars and COM)
  double wall_seconds = 0.0;             ///< stepping only (measurements excluded)
  double simulated_seconds = 0.0;
  std::uint64_t steps = 0;
  std::vector<Vec3> final_position;  ///< by particle id
  std::string failure;               ///< non-empty: the run went unstable (the message)
};

/// Restores `rolling`, applies the setting, runs `transient` s, then `window` s with `samples`
/// measurements.
DrumRun run_drum(const RollingState& rolling, const RunSettings& s, double transient, double window,
                 int samples);

/// Mean angle of the first and second half of a run's samples, and the standard error of the
/// mean angle over all samples (the noise of a time average over the window), degrees.
struct SteadyCheck {
  double first = 0.0;
  double second = 0.0;
  double noise = 0.0;
};
SteadyCheck steady_check(const DrumRun& run);

/// Relative standard error of the window mean of each drum observable (angle, KE, layer; COM
/// divided by the drum radius), the largest of them: the noise floor below which a drum error is
/// not resolved by the window. NaN with fewer than two samples.
double drum_noise_floor(const DrumRun& run, double drum_radius);

}  // namespace drumlab::bench
