#include "engine/analysis/flow_regime.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <fmt/format.h>

namespace drumlab {
namespace {

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

/// max - min of a centred moving average of `values` over `width` samples (shorter at the ends).
double smoothed_swing(const std::vector<double>& values, int width) {
  if (values.empty()) return 0.0;
  const auto n = static_cast<std::ptrdiff_t>(values.size());
  const std::ptrdiff_t half = std::max(width, 1) / 2;
  double lo = 0.0, hi = 0.0;
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const std::ptrdiff_t a = std::max<std::ptrdiff_t>(0, k - half);
    const std::ptrdiff_t b = std::min(n - 1, k + half);
    double sum = 0.0;
    for (std::ptrdiff_t j = a; j <= b; ++j) sum += values[static_cast<std::size_t>(j)];
    const double avg = sum / static_cast<double>(b - a + 1);
    lo = k == 0 ? avg : std::min(lo, avg);
    hi = k == 0 ? avg : std::max(hi, avg);
  }
  return hi - lo;
}

}  // namespace

std::string_view regime_name(FlowRegime regime) {
  switch (regime) {
    case FlowRegime::resting:
      return "resting";
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

std::vector<SurfaceHeight> mean_surface_profile(std::span<const DrumObservables> window) {
  std::map<long long, std::vector<double>> bins;  // bin centre (micrometres) -> heights
  std::size_t with_surface = 0;
  for (const auto& o : window) {
    if (o.surface_profile.empty()) continue;
    ++with_surface;
    for (const auto& s : o.surface_profile) bins[std::llround(s.h * 1e6)].push_back(s.u);
  }
  std::vector<SurfaceHeight> out;
  for (const auto& [key, heights] : bins) {
    if (2 * heights.size() < with_surface) continue;  // an edge bin seen in few samples
    out.push_back({static_cast<double>(key) * 1e-6, median(heights)});
  }
  return out;
}

RegimeEvidence classify_regime(std::span<const DrumObservables> window,
                               const FlowRegimeThresholds& t) {
  RegimeEvidence e;
  e.samples = window.size();
  std::vector<double> angles, curvatures;
  double wall = 0.0, field = 0.0, radius = 0.0;
  bool profiles = false;
  for (const auto& o : window) {
    field += o.field;
    radius += o.radius;
    profiles = profiles || !o.surface_profile.empty();
    if (o.surface_found) curvatures.push_back(o.surface_curvature);
    e.airborne_fraction += o.airborne_fraction;
    e.upper_fraction += o.upper_fraction;
    e.com_offset += o.com_offset;
    e.relative_speed += o.relative_speed;
    wall += o.wall_speed;
    if (o.surface_found) angles.push_back(o.angle_of_repose_deg);
  }
  if (angles.empty()) return e;
  const auto n = static_cast<double>(window.size());
  e.airborne_fraction /= n;
  e.upper_fraction /= n;
  e.com_offset /= n;
  e.relative_speed /= n;
  wall /= n;
  e.wall_speed = wall;
  e.rest_scale = std::sqrt(std::max(0.0, field / n * radius / n));
  e.speed_ratio = wall > 0.0 ? e.relative_speed / wall : 0.0;

  double sum = 0.0, var = 0.0;
  for (const double a : angles) sum += a;
  e.mean_angle_deg = sum / static_cast<double>(angles.size());
  const auto [lo, hi] = std::minmax_element(angles.begin(), angles.end());
  e.angle_swing_deg = *hi - *lo;
  e.smoothed_swing_deg = smoothed_swing(angles, t.smoothing);

  std::size_t still = 0;
  for (const auto& o : window) {
    if (o.relative_speed <= t.still_speed * e.relative_speed) ++still;
    var += std::pow(o.relative_speed - e.relative_speed, 2);
  }
  e.still_share = static_cast<double>(still) / n;
  e.intermittency = e.relative_speed > 0.0 ? std::sqrt(var / n) / e.relative_speed : 0.0;

  if (const auto fit = fit_surface_profile(mean_surface_profile(window), t.end_exclusion)) {
    e.profile_found = true;
    e.profile_angle_deg = fit->angle_deg;
    e.curvature = fit->curvature;
  } else {
    e.profile_angle_deg = e.mean_angle_deg;
    if (!profiles) {  // samples from a table: their own curvatures
      e.sample_curvature = true;
      e.curvature = median(curvatures);
    }
  }

  const double rest = t.rest_speed * e.rest_scale;
  if (e.wall_speed <= rest && e.relative_speed <= rest) {
    e.regime = FlowRegime::resting;
  } else if (e.upper_fraction >= t.upper_fraction && e.com_offset <= t.com_offset) {
    e.regime = FlowRegime::centrifuging;
  } else if (e.airborne_fraction >= t.airborne_fraction) {
    e.regime = FlowRegime::cataracting;
  } else if (e.still_share >= t.still_share || e.intermittency >= t.intermittency) {
    e.regime = FlowRegime::slumping;
  } else if (e.curvature >= t.curvature) {
    e.regime = FlowRegime::cascading;
  } else {
    e.regime = FlowRegime::rolling;
  }
  return e;
}

std::string regime_reason(const RegimeEvidence& e, const FlowRegimeThresholds& t) {
  switch (e.regime) {
    case FlowRegime::resting:
      return fmt::format("not driven: wall {:.2g} m/s and relative speed {:.2g} m/s <= {} x {:.3g}",
                         e.wall_speed, e.relative_speed, t.rest_speed, e.rest_scale);
    case FlowRegime::centrifuging:
      return fmt::format("bed carried round (upper share {:.2f} >= {})", e.upper_fraction,
                         t.upper_fraction);
    case FlowRegime::cataracting:
      return fmt::format("in flight {:.3f} >= {}", e.airborne_fraction, t.airborne_fraction);
    case FlowRegime::slumping:
      return fmt::format("still share {:.2f} (rule: >= {}), intermittency {:.2f} (rule: >= {})",
                         e.still_share, t.still_share, e.intermittency, t.intermittency);
    case FlowRegime::cascading:
    case FlowRegime::rolling:
      return fmt::format(
          "in flight {:.3f} < {}, still share {:.2f} < {}, intermittency {:.2f} < {}, {}curvature "
          "{:.3f} {} {}",
          e.airborne_fraction, t.airborne_fraction, e.still_share, t.still_share, e.intermittency,
          t.intermittency, e.sample_curvature ? "samples' " : "", e.curvature,
          e.regime == FlowRegime::cascading ? ">=" : "<", t.curvature);
    case FlowRegime::unknown:
      break;
  }
  return "no surface found";
}

}  // namespace drumlab
