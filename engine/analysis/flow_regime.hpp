#pragma once
// Classifies the flow regime of a rotating drum (slumping, rolling, cascading, cataracting,
// centrifuging) from drum observables sampled over a time window (see drum_observables.hpp).
//
// Window statistics (RegimeEvidence):
// * relative speed: each sample's mean particle speed relative to a rigid rotation with the drum.
//   In any steady regime the material the drum lifts must stream back, so the window mean is of
//   order omega R; a continuous flow stays near that mean in every sample, while a slumping bed
//   turns as a solid body (relative speed ~0) between short avalanches that carry the whole flux.
//   A sample is *still* when its relative speed is <= still_speed x the window mean; still_share
//   is the share of still samples, intermittency the coefficient of variation (std / mean).
//   Both are means over all particles, so they do not suffer from the noise of a surface fit.
// * window-mean surface: the surface profiles of all samples are averaged bin by bin (median
//   over the samples; bins present in fewer than half of the samples dropped), then the line and
//   the cubic are fitted to its central part (end_exclusion at each end). Its angle is the dynamic
//   angle of repose (profile_angle_deg); its curvature (max |cubic - line| / chord) tells a flat
//   from an S-shaped surface without the per-sample noise of a surface 10-20 particles wide.
// * the per-sample fitted angle: mean, raw swing (max - min), and the swing of the angle smoothed
//   by a centred moving average over `smoothing` samples (the avalanche saw-tooth; reported as
//   evidence, not used by the rules: in a small drum the per-sample noise of several degrees makes
//   even the smoothed swing a few degrees in every regime).
//
// The rules, applied in this order (thresholds in FlowRegimeThresholds):
// 0. resting: nothing drives the bed and it does not flow: the wall's speed against the field
//    (drum_observables.hpp: |omega - field_omega| R) and the mean relative speed are both
//    <= rest_speed (1e-3) x sqrt(field R), a drive Froude number below 1e-6. A plain drum at
//    rest, or a planetary pot turning with its arm (k = 0), whose bed sits against the far wall
//    and turns with it. (The slowest drum of `bench regimes`, Fr = 3e-5, drives at 5.5e-3.)
// 1. centrifuging: the bed is carried around the whole mantle as a ring. Mean share of particle
//    centres above the axis >= upper_fraction (0.35) and the centre of mass within
//    com_offset (0.15) * R of the axis.
// 2. cataracting: particles are thrown off the rising bed. Mean share of particles in free
//    flight >= airborne_fraction (0.02).
// 3. slumping: intermittent avalanches. still_share >= still_share (0.3), with still_speed 0.25:
//    at least 30 % of the samples move at <= 1/4 of the window's mean relative speed; or
//    intermittency >= intermittency (0.6), which also catches a quiet phase that creeps instead
//    of resting. For a two-state flow (a share f of the time flowing, at rest otherwise) the
//    intermittency is sqrt((1 - f) / f): 0.6 means f = 0.74, the same ~30 % quiet share; a
//    continuous flow stays at 0.1-0.3 (the default `bench regimes` run, Fr >= 1e-3).
// 4. cascading: a continuous flow with a curved (S- or kidney-shaped) surface: curvature of the
//    window-mean surface >= curvature (0.02).
// 5. rolling: otherwise (a continuous flow with a flat surface).
// A window whose samples found no surface at all (e.g. an empty drum) is `unknown`. Samples read
// back from a table (`drumlab sweep`) carry no surface profiles: the curvature is then the median
// of the samples' own curvatures (noisier than the window-mean surface's; flagged in evidence).
// The thresholds are heuristics chosen for beds of ~25-50 % fill and samples spaced more finely
// than an avalanche cycle; they are the documented definition, not a universal law.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/analysis/drum_observables.hpp"

namespace drumlab {

enum class FlowRegime { unknown, resting, slumping, rolling, cascading, cataracting, centrifuging };
/// The regimes in the order above (resting to centrifuging), for maps and legends.
inline constexpr FlowRegime kFlowRegimes[] = {FlowRegime::resting,     FlowRegime::slumping,
                                              FlowRegime::rolling,     FlowRegime::cascading,
                                              FlowRegime::cataracting, FlowRegime::centrifuging};

std::string_view regime_name(FlowRegime regime);

struct FlowRegimeThresholds {
  double rest_speed = 1e-3;  ///< resting: drive and relative speed <= this x sqrt(field R)
  double upper_fraction = 0.35;
  double com_offset = 0.15;
  double airborne_fraction = 0.02;
  double still_speed = 0.25;  ///< still sample: relative speed <= still_speed x window mean
  double still_share = 0.3;
  double intermittency = 0.6;  ///< std / mean of the samples' relative speed
  double curvature = 0.02;     ///< of the window-mean surface
  int smoothing = 5;           ///< samples in the moving average of the angle
  double end_exclusion = 0.2;  ///< for the window-mean surface fit, as in ObservableOptions
};

/// Window statistics the classification used (means over the samples unless stated).
struct RegimeEvidence {
  FlowRegime regime = FlowRegime::unknown;
  std::size_t samples = 0;
  double mean_angle_deg = 0.0;      ///< mean of the per-sample fitted angles
  double angle_swing_deg = 0.0;     ///< max - min of the per-sample angles
  double smoothed_swing_deg = 0.0;  ///< max - min of the moving-average angle
  double profile_angle_deg = 0.0;   ///< angle of the window-mean surface (dynamic angle of repose)
  double curvature = 0.0;           ///< curvature of the window-mean surface
  bool profile_found = false;       ///< the window-mean surface had >= 3 central points
  bool sample_curvature = false;    ///< no profiles: `curvature` is the samples' median
  double still_share = 0.0;         ///< share of still samples (see the header comment)
  double intermittency = 0.0;       ///< std / mean of the samples' relative speed
  double relative_speed = 0.0;      ///< m/s
  double wall_speed = 0.0;          ///< the wall's speed against the field, m/s
  double rest_scale = 0.0;          ///< sqrt(field R), m/s (mean field)
  double speed_ratio = 0.0;         ///< relative_speed / wall_speed; 0 when the wall is at rest
  double airborne_fraction = 0.0;
  double upper_fraction = 0.0;
  double com_offset = 0.0;
};

RegimeEvidence classify_regime(std::span<const DrumObservables> window,
                               const FlowRegimeThresholds& thresholds = {});

/// The rule that decided `e.regime`, with its figures against the thresholds, in one phrase.
std::string regime_reason(const RegimeEvidence& e, const FlowRegimeThresholds& thresholds = {});

/// The window-mean surface profile (see the header comment); empty without surfaces.
std::vector<SurfaceHeight> mean_surface_profile(std::span<const DrumObservables> window);

}  // namespace drumlab
