#include "engine/analysis/flow_regime.hpp"

#include <algorithm>

namespace drumlab {

std::string_view regime_name(FlowRegime regime) {
  switch (regime) {
    case FlowRegime::slumping:
      return "slumping";
    case FlowRegime::rolling:
      return "rolling";
    case FlowRegime::cascading:
      return "cascading";
    case FlowRegime::cataracting:
      return "cataracting";
    case FlowRegime::centrifuging:
      return "centrifuging";
    case FlowRegime::unknown:
      break;
  }
  return "unknown";
}

RegimeEvidence classify_regime(std::span<const DrumObservables> window,
                               const FlowRegimeThresholds& t) {
  RegimeEvidence e;
  e.samples = window.size();
  std::size_t with_surface = 0, still = 0;
  double lo = 0.0, hi = 0.0;
  for (const auto& o : window) {
    e.airborne_fraction += o.airborne_fraction;
    e.upper_fraction += o.upper_fraction;
    e.com_offset += o.com_offset;
    if (!o.surface_found) continue;
    lo = with_surface == 0 ? o.angle_of_repose_deg : std::min(lo, o.angle_of_repose_deg);
    hi = with_surface == 0 ? o.angle_of_repose_deg : std::max(hi, o.angle_of_repose_deg);
    ++with_surface;
    e.mean_angle_deg += o.angle_of_repose_deg;
    e.curvature += o.surface_curvature;
    if (o.flowing_layer_thickness <= 0.0) ++still;
  }
  if (with_surface == 0) return e;
  const auto n = static_cast<double>(window.size());
  const auto ns = static_cast<double>(with_surface);
  e.airborne_fraction /= n;
  e.upper_fraction /= n;
  e.com_offset /= n;
  e.mean_angle_deg /= ns;
  e.curvature /= ns;
  e.still_share = static_cast<double>(still) / ns;
  e.angle_swing_deg = hi - lo;

  if (e.upper_fraction >= t.upper_fraction && e.com_offset <= t.com_offset) {
    e.regime = FlowRegime::centrifuging;
  } else if (e.airborne_fraction >= t.airborne_fraction) {
    e.regime = FlowRegime::cataracting;
  } else if (e.still_share >= t.still_share || e.angle_swing_deg > t.angle_swing_deg) {
    e.regime = FlowRegime::slumping;
  } else if (e.curvature >= t.curvature) {
    e.regime = FlowRegime::cascading;
  } else {
    e.regime = FlowRegime::rolling;
  }
  return e;
}

}  // namespace drumlab
