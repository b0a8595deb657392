#pragma once
// Grouped bar charts for the benchmarks (`drumlab bench`), drawn with VTK's charts into an
// offscreen OSMesa buffer and written as PNG. Several panels sit side by side in one image.
#include <filesystem>
#include <string>
#include <vector>

namespace drumlab::render {

struct BarSeries {
  std::string name;            ///< legend entry
  std::vector<double> values;  ///< one per category; NaN: no bar
};

struct BarPanel {
  std::string title;
  std::string y_label;
  std::vector<std::string> categories;  ///< x axis labels (e.g. search methods)
  std::vector<BarSeries> series;
  /// Log10 axis: bars show log10(value), ticks are labelled with the decades. Values must be > 0
  /// (others get no bar).
  bool log_y = false;
};

/// Draws the panels side by side (each width / panels.size() wide) and writes `file` as PNG.
/// Throws InputError if the file cannot be written, std::runtime_error if OSMesa fails.
void write_bar_charts(const std::vector<BarPanel>& panels, const std::filesystem::path& file,
                      int width = 1400, int height = 600);

}  // namespace drumlab::render
