#include "render/bench_chart.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include "render/chart_canvas.hpp"
#include "render/frame_writer.hpp"

namespace drumlab::render {

namespace {

constexpr double kSeriesColours[][3] = {
    {31, 119, 180}, {255, 127, 14}, {44, 160, 44}, {214, 39, 40}, {148, 103, 189}};

/// Lowest decade of a log axis: below the smallest positive value, so that a value of exactly
/// 1, 10, ... still gets a visible bar (bars start at the axis origin).
int lowest_decade(const BarPanel& panel) {
  double low = std::numeric_limits<double>::infinity();
  for (const BarSeries& s : panel.series) {
    for (const double v : s.values) {
      if (std::isfinite(v) && v > 0.0) low = std::min(low, v);
    }
  }
  return std::isfinite(low) ? static_cast<int>(std::floor(std::log10(low) - 0.25)) : 0;
}

/// Bar height: the value, or on a log axis its decades above the lowest decade (0: no bar).
double shown(double v, const BarPanel& panel, int lo) {
  if (!std::isfinite(v)) return 0.0;
  if (!panel.log_y) return v;
  return v > 0.0 ? std::log10(v) - lo : 0.0;
}

/// Fills one chart: a table with an x column (1..n) and a column per series, one bar plot each.
void fill_chart(vtkChartXY* chart, const BarPanel& panel) {
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> x;
  x->SetName("x");
  table->AddColumn(x);
  for (const BarSeries& s : panel.series) {
    vtkNew<vtkDoubleArray> column;
    column->SetName(s.name.c_str());
    table->AddColumn(column);
  }
  const auto n = static_cast<vtkIdType>(panel.categories.size());
  table->SetNumberOfRows(n);
  const int lo = panel.log_y ? lowest_decade(panel) : 0;
  double top = 0.0;
  for (vtkIdType r = 0; r < n; ++r) {
    table->SetValue(r, 0, static_cast<double>(r + 1));
    for (std::size_t c = 0; c < panel.series.size(); ++c) {
      const auto& values = panel.series[c].values;
      const double v =
          static_cast<std::size_t>(r) < values.size() ? shown(values[r], panel, lo) : 0.0;
      table->SetValue(r, static_cast<vtkIdType>(c + 1), v);
      top = std::max(top, v);
    }
  }
  for (std::size_t c = 0; c < panel.series.size(); ++c) {
    vtkPlot* bar = chart->AddPlot(vtkChart::BAR);
    bar->SetInputData(table, 0, static_cast<vtkIdType>(c + 1));
    const auto& rgb = kSeriesColours[c % std::size(kSeriesColours)];
    bar->SetColor(static_cast<unsigned char>(rgb[0]), static_cast<unsigned char>(rgb[1]),
                  static_cast<unsigned char>(rgb[2]), 255);
    bar->SetLabel(panel.series[c].name);
  }
  chart->SetTitle(panel.title);
  chart->GetTitleProperties()->SetFontSize(16);
  chart->SetShowLegend(panel.series.size() > 1);

  vtkAxis* xa = chart->GetAxis(vtkAxis::BOTTOM);
  vtkNew<vtkDoubleArray> xpos;
  vtkNew<vtkStringArray> xlabels;
  for (vtkIdType r = 0; r < n; ++r) {
    xpos->InsertNextValue(static_cast<double>(r + 1));
    xlabels->InsertNextValue(panel.categories[static_cast<std::size_t>(r)]);
  }
  xa->SetCustomTickPositions(xpos, xlabels);
  xa->SetBehavior(vtkAxis::FIXED);
  xa->SetRange(0.4, static_cast<double>(n) + 0.6);
  xa->SetTitle("");
  xa->GetLabelProperties()->SetOrientation(45.0);
  xa->GetLabelProperties()->SetFontSize(12);

  vtkAxis* ya = chart->GetAxis(vtkAxis::LEFT);
  ya->SetTitle(panel.y_label);
  ya->SetBehavior(vtkAxis::FIXED);
  if (panel.log_y) {
    const int decades = std::max(1, static_cast<int>(std::ceil(top - 1e-9)));
    vtkNew<vtkDoubleArray> ypos;
    vtkNew<vtkStringArray> ylabels;
    for (int d = 0; d <= decades; ++d) {
      ypos->InsertNextValue(d);
      ylabels->InsertNextValue(fmt::format("{:g}", std::pow(10.0, lo + d)));
    }
    ya->SetCustomTickPositions(ypos, ylabels);
    ya->SetRange(0.0, decades);
  } else {
    ya->SetRange(0.0, top > 0.0 ? 1.08 * top : 1.0);
  }
}

}  // namespace

void write_bar_charts(const std::vector<BarPanel>& panels, const std::filesystem::path& file,
                      int width, int height) {
  if (panels.empty()) throw std::invalid_argument("write_bar_charts: no panels");
  write_chart_panels(
      panels.size(), [&](vtkChartXY* chart, std::size_t k) { fill_chart(chart, panels[k]); }, file,
      width, height);
}

}  // namespace drumlab::render
