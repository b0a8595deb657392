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

/// Each point's error bar as a two-point line in the series' colour, without a legend entry.
void add_error_bars(vtkChartXY* chart, const XYSeries& s, const XYPanel& panel, vtkPlot* like) {
  for (std::size_t k = 0; k < s.y_error.size() && k < s.x.size() && k < s.y.size(); ++k) {
    const double lo = s.y[k] - s.y_error[k], hi = s.y[k] + s.y_error[k];
    if (!(s.y_error[k] > 0.0) || !drawable(s.x[k], panel.log_x) || !drawable(lo, panel.log_y) ||
        !drawable(hi, panel.log_y)) {
      continue;
    }
    vtkNew<vtkTable> table;
    vtkNew<vtkDoubleArray> x, y;
    x->SetName("x");
    y->SetName("error");
    const double xv = panel.log_x ? std::log10(s.x[k]) : s.x[k];
    for (const double v : {lo, hi}) {
      x->InsertNextValue(xv);
      y->InsertNextValue(panel.log_y ? std::log10(v) : v);
    }
    table->AddColumn(x);
    table->AddColumn(y);
    vtkPlot* bar = chart->AddPlot(vtkChart::LINE);
    bar->SetInputData(table, 0, 1);
    bar->SetLegendVisibility(false);
    unsigned char rgb[3];
    like->GetColor(rgb);
    bar->SetColor(rgb[0], rgb[1], rgb[2], 255);
    bar->SetWidth(1.5f);
  }
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
  const bool points_only = s.markers_only || x->GetNumberOfTuples() == 1;
  vtkPlot* line = chart->AddPlot(points_only ? vtkChart::POINTS : vtkChart::LINE);
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
  add_error_bars(chart, s, panel, line);
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

/// Linear axes of a panel with markers or error bars: the points and bars with a margin, so that
/// none sits on the frame.
void pad_linear_axes(vtkChartXY* chart, const XYPanel& panel) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  bool padded = false;
  for (const XYSeries& s : panel.series) {
    padded = padded || s.markers_only || !s.y_error.empty();
    for (std::size_t k = 0; k < s.x.size() && k < s.y.size(); ++k) {
      const double e = k < s.y_error.size() && std::isfinite(s.y_error[k]) ? s.y_error[k] : 0.0;
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      x_lo = std::min(x_lo, s.x[k]);
      x_hi = std::max(x_hi, s.x[k]);
      y_lo = std::min(y_lo, s.y[k] - e);
      y_hi = std::max(y_hi, s.y[k] + e);
    }
  }
  if (!padded || !std::isfinite(x_lo)) return;
  const auto set = [](vtkAxis* axis, double lo, double hi) {
    const double margin = hi > lo ? 0.08 * (hi - lo) : std::max(1.0, std::abs(lo)) * 0.1;
    axis->SetBehavior(vtkAxis::FIXED);
    axis->SetRange(lo - margin, hi + margin);
  };
  if (!panel.log_x) set(chart->GetAxis(vtkAxis::BOTTOM), x_lo, x_hi);
  if (!panel.log_y) set(chart->GetAxis(vtkAxis::LEFT), y_lo, y_hi);
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
  pad_linear_axes(chart, panel);
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
