#include "render/xy_chart.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlotPoints.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include "render/chart_canvas.hpp"
#include "render/frame_writer.hpp"

namespace drumlab::render {

namespace {

constexpr unsigned char kColours[][3] = {{31, 119, 180}, {255, 127, 14},  {44, 160, 44},
                                         {214, 39, 40},  {148, 103, 189}, {140, 86, 75}};

bool drawable(double v, bool log) {
  return std::isfinite(v) && (!log || v > 0.0);
}

void add_series(vtkChartXY* chart, const XYSeries& s, const XYPanel& panel, std::size_t index) {
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> x;
  x->SetName("x");
  vtkNew<vtkDoubleArray> y;
  y->SetName(s.name.c_str());
  for (std::size_t k = 0; k < s.x.size() && k < s.y.size(); ++k) {
    if (!drawable(s.x[k], panel.log_x) || !drawable(s.y[k], panel.log_y)) continue;
    x->InsertNextValue(panel.log_x ? std::log10(s.x[k]) : s.x[k]);
    y->InsertNextValue(panel.log_y ? std::log10(s.y[k]) : s.y[k]);
  }
  if (x->GetNumberOfTuples() == 0) return;
  table->AddColumn(x);
  table->AddColumn(y);
  // A line needs two points; a single point is drawn as a marker.
  vtkPlot* line = chart->AddPlot(x->GetNumberOfTuples() > 1 ? vtkChart::LINE : vtkChart::POINTS);
  line->SetInputData(table, 0, 1);
  line->SetLabel(s.name);
  if (s.emphasised) {
    line->SetColor(0, 0, 0, 255);
    line->SetWidth(3.0f);
  } else {
    const auto& rgb = kColours[index % std::size(kColours)];
    line->SetColor(rgb[0], rgb[1], rgb[2], 255);
    line->SetWidth(2.0f);
  }
  if (auto* points = vtkPlotPoints::SafeDownCast(line)) {
    points->SetMarkerStyle(s.emphasised ? vtkPlotPoints::SQUARE : vtkPlotPoints::CIRCLE);
    points->SetMarkerSize(s.emphasised ? 12.0f : 8.0f);
  }
}

/// Range of the drawn values along one axis (log10 when `log`); {inf, -inf} when none.
std::pair<double, double> drawn_range(const XYPanel& panel, bool y_axis) {
  const bool log = y_axis ? panel.log_y : panel.log_x;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const XYSeries& s : panel.series) {
    for (std::size_t k = 0; k < s.x.size() && k < s.y.size(); ++k) {
      if (!drawable(s.x[k], panel.log_x) || !drawable(s.y[k], panel.log_y)) continue;
      const double v = y_axis ? s.y[k] : s.x[k];
      lo = std::min(lo, log ? std::log10(v) : v);
      hi = std::max(hi, log ? std::log10(v) : v);
    }
  }
  return {lo, hi};
}

/// A log axis drawn from log10 values: fixed range and ticks at 1, 2, 5 x 10^k, labelled with
/// the values themselves. (VTK 9.1's own log axes drew no lines in the offscreen context.)
void set_log_axis(vtkAxis* axis, std::pair<double, double> range) {
  auto [lo, hi] = range;
  if (!std::isfinite(lo)) return;
  if (hi - lo < 0.3) {
    lo -= 0.15;
    hi += 0.15;
  }
  lo -= 0.05 * (hi - lo);
  hi += 0.05 * (hi - lo);
  vtkNew<vtkDoubleArray> pos;
  vtkNew<vtkStringArray> labels;
  const bool few_decades = hi - lo < 3.0;
  for (int d = static_cast<int>(std::floor(lo)); d <= static_cast<int>(std::ceil(hi)); ++d) {
    for (const double m : {1.0, 2.0, 5.0}) {
      if (m != 1.0 && !few_decades) continue;
      const double t = d + std::log10(m);
      if (t < lo || t > hi) continue;
      pos->InsertNextValue(t);
      labels->InsertNextValue(fmt::format("{:g}", m * std::pow(10.0, d)));
    }
  }
  axis->SetCustomTickPositions(pos, labels);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetRange(lo, hi);
}

void fill_chart(vtkChartXY* chart, const XYPanel& panel) {
  std::size_t colour = 0;
  for (const XYSeries& s : panel.series) {
    add_series(chart, s, panel, s.emphasised ? 0 : colour);
    if (!s.emphasised) ++colour;
  }
  chart->SetTitle(panel.title);
  chart->GetTitleProperties()->SetFontSize(15);
  chart->SetShowLegend(true);
  vtkAxis* xa = chart->GetAxis(vtkAxis::BOTTOM);
  xa->SetTitle(panel.x_label);
  if (panel.log_x) set_log_axis(xa, drawn_range(panel, false));
  vtkAxis* ya = chart->GetAxis(vtkAxis::LEFT);
  ya->SetTitle(panel.y_label);
  if (panel.log_y) set_log_axis(ya, drawn_range(panel, true));
}

}  // namespace

void write_xy_charts(const std::vector<XYPanel>& panels, const std::filesystem::path& file,
                     int width, int height) {
  if (panels.empty()) throw std::invalid_argument("write_xy_charts: no panels");
  write_chart_panels(
      panels.size(), [&](vtkChartXY* chart, std::size_t k) { fill_chart(chart, panels[k]); }, file,
      width, height);
}

}  // namespace drumlab::render
