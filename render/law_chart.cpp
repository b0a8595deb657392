#include "render/law_chart.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "render/xy_chart.hpp"

namespace drumlab::render {

void write_law_chart(const LawCurve& curve, const std::filesystem::path& file) {
  constexpr double kMm = 1e3;  // gap in mm
  constexpr double kMn = 1e3;  // force in mN
  XYSeries approach{"approach", {}, {}, false};
  XYSeries retreat{"retreat (pulled apart)", {}, {}, true};
  double lo = 0.0, hi = 0.0;
  for (const LawSample& s : curve.samples) {
    XYSeries& series = s.retreat ? retreat : approach;
    series.x.push_back(s.gap * kMm);
    series.y.push_back(s.normal_force * kMn);
    lo = std::min(lo, s.normal_force * kMn);
    hi = std::max(hi, s.normal_force * kMn);
  }
  XYPanel panel;
  panel.title = fmt::format("drumlab law: {}", curve.label);
  panel.x_label = "surface gap s (mm), < 0: overlap";
  panel.y_label = "normal force (mN), > 0 repulsive";
  panel.series = {approach, retreat};
  if (std::isfinite(curve.rupture_gap)) {
    const double x = 0.5 * (curve.rupture_gap + curve.last_bridged_gap) * kMm;
    panel.series.push_back({fmt::format("rupture, s = {:.4g} mm (s_rup = {:.4g} mm)", x,
                                        curve.predicted_rupture * kMm),
                            {x, x},
                            {lo, 0.25 * hi},
                            false});
  }
  write_xy_charts({panel}, file, 1200, 700);
}

}  // namespace drumlab::render
