#pragma once
// The offscreen canvas the benchmark charts share: `count` vtkChartXY panels side by side in one
// OSMesa image, written as PNG. Each chart module only fills its panels.
#include <cstddef>
#include <filesystem>
#include <functional>

class vtkChartXY;

namespace drumlab::render {

/// Lays out `count` charts side by side (each width / count wide), calls fill(chart, k) for
/// panel k, renders offscreen and writes `file` as PNG. Throws InputError if the file cannot be
/// written, std::runtime_error if OSMesa fails.
void write_chart_panels(std::size_t count,
                        const std::function<void(vtkChartXY*, std::size_t)>& fill,
                        const std::filesystem::path& file, int width, int height);

}  // namespace drumlab::render
