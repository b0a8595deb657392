#pragma once
// Classifies the flow regime of a rotating drum (slumping, rolling, cascading, cataracting,
// centrifuging) from drum observables sampled over a time window (see drum_observables.hpp).
//
// The rules, applied in this order to the window's samples (thresholds in FlowRegimeThresholds):
// 1. centrifuging: the bed is carried around the whole mantle. Mean share of particle centres
//    above the axis >= upper_fraction and the centre of mass within com_offset * R of the axis.
// 2. cataracting: particles are thrown off the rising bed. Mean share of particles in free
//    flight >= airborne_fraction.
// 3. slumping: the bed turns as a solid body and relaxes in discrete avalanches. At least
//    still_share of the samples show no flowing layer (surface not moving downhill), or the angle
//    of repose swings by more than angle_swing_deg (max - min) over the window.
// 4. cascading: a continuous flow with a curved (S- or kidney-shaped) surface. Mean surface
//    curvature (cubic vs line deviation / chord) >= curvature.
// 5. rolling: otherwise (a continuous flow with a flat surface).
// A window whose samples found no surface at all (e.g. an empty drum) is `unknown`.
// The thresholds are heuristics chosen for beds of ~25-50 % fill; they are the documented
// definition, not a universal law.
#include <span>
#include <string_view>

#include "engine/analysis/drum_observables.hpp"

namespace drumlab {

enum class FlowRegime { unknown, slumping, rolling, cascading, cataracting, centrifuging };

std::string_view regime_name(FlowRegime regime);

struct FlowRegimeThresholds {
  double upper_fraction = 0.35;
  double com_offset = 0.15;
  double airborne_fraction = 0.02;
  double still_share = 0.3;
  double angle_swing_deg = 5.0;
  double curvature = 0.02;
};

/// Window statistics the classification used (means over the samples unless stated).
struct RegimeEvidence {
  FlowRegime regime = FlowRegime::unknown;
  std::size_t samples = 0;
  double mean_angle_deg = 0.0;
  double angle_swing_deg = 0.0;  ///< max - min over samples with a surface
  double still_share = 0.0;      ///< share of samples without a flowing layer
  double curvature = 0.0;
  double airborne_fraction = 0.0;
  double upper_fraction = 0.0;
  double com_offset = 0.0;
};

RegimeEvidence classify_regime(std::span<const DrumObservables> window,
                               const FlowRegimeThresholds& thresholds = {});

}  // namespace drumlab
