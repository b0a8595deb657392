#include "render/agglomerate_chart.hpp"

#include <fmt/format.h>

#include "render/xy_chart.hpp"

namespace drumlab::render {

void write_agglomerate_chart(const std::vector<AgglomerateStats>& rows,
                             const std::filesystem::path& file) {
  if (rows.empty()) {
    throw InputError(fmt::format("{}: no frames to draw the size distribution of", file.string()));
  }
  XYPanel sizes{fmt::format("volume-equivalent diameter ({})", rows.front().criterion),
                "time (s)",
                "diameter (mm)",
                {}};
  XYPanel counts{"agglomerates (size >= 2)", "time (s)", "count / primaries / %", {}};
  XYSeries d10{"d10", {}, {}}, d50{"d50", {}, {}, true}, d90{"d90", {}, {}};
  XYSeries count{"count", {}, {}}, largest{"largest (primaries)", {}, {}},
      share{"largest plain component (% of bed)", {}, {}};
  for (const AgglomerateStats& r : rows) {
    for (XYSeries* s : {&d10, &d50, &d90, &count, &largest, &share}) s->x.push_back(r.time);
    d10.y.push_back(1000.0 * r.d10);
    d50.y.push_back(1000.0 * r.d50);
    d90.y.push_back(1000.0 * r.d90);
    count.y.push_back(static_cast<double>(r.count));
    largest.y.push_back(static_cast<double>(r.largest));
    share.y.push_back(100.0 * r.largest_plain_share);
  }
  sizes.series = {d10, d50, d90};
  counts.series = {count, largest, share};
  write_xy_charts({sizes, counts}, file);
}

}  // namespace drumlab::render
