#include "render/growth_chart.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "render/xy_chart.hpp"

namespace drumlab::render {

void write_growth_chart(const std::vector<AgglomerateStats>& rows,
                        const std::vector<GrowthPhase>& phases, const std::filesystem::path& file) {
  if (rows.empty()) throw InputError(fmt::format("{}: no rows to chart", file.string()));
  const bool sprayed = rows.back().spray.sprayed > 0.0;
  std::vector<double> x;
  for (const AgglomerateStats& r : rows) x.push_back(sprayed ? r.spray.sprayed : r.time);
  const std::string x_label = sprayed ? "liquid sprayed (m^3)" : "time (s)";
  const auto column = [&](auto value) {
    std::vector<double> y;
    for (const AgglomerateStats& r : rows) y.push_back(value(r));
    return y;
  };
  XYPanel sizes{
      fmt::format("granule size ({})", rows.front().criterion), x_label, "diameter (mm)", {}};
  sizes.series = {{"d10", x, column([](const AgglomerateStats& r) { return 1e3 * r.d10; })},
                  {"d50", x, column([](const AgglomerateStats& r) { return 1e3 * r.d50; }), true},
                  {"d90", x, column([](const AgglomerateStats& r) { return 1e3 * r.d90; })}};
  XYPanel counts{"granules", x_label, "count / primaries", {}};
  counts.series = {
      {"granules (size >= 2)", x,
       column([](const AgglomerateStats& r) { return static_cast<double>(r.count); }), true},
      {"largest (primaries)", x,
       column([](const AgglomerateStats& r) { return static_cast<double>(r.largest); })}};
  // Each phase's start as a vertical line spanning its panel's values.
  for (XYPanel* panel : {&sizes, &counts}) {
    double low = 0.0, high = 0.0;
    for (const XYSeries& s : panel->series) {
      for (const double y : s.y) high = std::max(high, y);
    }
    for (const GrowthPhase& p : phases) {
      panel->series.push_back({fmt::format("{} from {:.3g}", p.name, x[p.first]),
                               {x[p.first], x[p.first]},
                               {low, high}});
    }
  }
  // Against time too: after the spray stops the liquid axis stands still, time does not.
  std::vector<double> t;
  for (const AgglomerateStats& r : rows) t.push_back(r.time);
  XYPanel in_time{"against time", "time (s)", "d50 (mm) / granules / 10", {}};
  in_time.series = {
      {"d50 (mm)", t, column([](const AgglomerateStats& r) { return 1e3 * r.d50; }), true},
      {"granules / 10", t,
       column([](const AgglomerateStats& r) { return 0.1 * static_cast<double>(r.count); })}};
  double high = 0.0;
  for (const XYSeries& s : in_time.series) {
    for (const double y : s.y) high = std::max(high, y);
  }
  for (const GrowthPhase& p : phases) {
    in_time.series.push_back({fmt::format("{} from t = {:.3g} s", p.name, t[p.first]),
                              {t[p.first], t[p.first]},
                              {0.0, high}});
  }
  write_xy_charts({sizes, counts, in_time}, file, 2400, 600);
}

}  // namespace drumlab::render
