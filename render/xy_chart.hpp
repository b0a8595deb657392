#pragma once
// XY line charts for the benchmarks (e.g. error against run time, log-log), drawn with VTK's
// vtkChartXY into an offscreen OSMesa buffer and written as PNG. Panels sit side by side.
#include <filesystem>
#include <string>
#include <vector>

namespace drumlab::render {

struct XYSeries {
  std::string name;       ///< legend entry
  std::vector<double> x;  ///< points in drawing order; pairs with a non-finite value are skipped
  std::vector<double> y;
  bool emphasised = false;        ///< drawn black and thicker (e.g. a Pareto front)
  bool markers_only = false;      ///< points without a connecting line
  std::vector<double> y_error{};  ///< if given: a bar from y - e to y + e at each point
};

struct XYPanel {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<XYSeries> series;
  bool log_x = false;  ///< log10 axes (ticks 1, 2, 5 x 10^k): points with a value <= 0 are skipped
  bool log_y = false;
};

/// Draws the panels side by side and writes `file` as PNG. Throws InputError if the file cannot
/// be written, std::invalid_argument without panels, std::runtime_error if OSMesa fails.
void write_xy_charts(const std::vector<XYPanel>& panels, const std::filesystem::path& file,
                     int width = 1600, int height = 600);

}  // namespace drumlab::render
