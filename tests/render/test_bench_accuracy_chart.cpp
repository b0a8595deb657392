// The XY chart of `drumlab bench accuracy` (render/xy_chart.hpp): a log-log panel really draws its
// curves (VTK 9.1's own log axes drew axes but no lines offscreen, which this test catches), and
// bad input is refused.
#include <gtest/gtest.h>

#include <filesystem>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include "render/xy_chart.hpp"

namespace drumlab {
namespace {

/// Pixels of the PNG within 40 levels of the colour in every channel.
std::size_t pixels_near(const std::filesystem::path& file, int r, int g, int b) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkImageData* img = reader->GetOutput();
  int dims[3] = {0, 0, 0};
  img->GetDimensions(dims);
  const int comps = img->GetNumberOfScalarComponents();
  std::size_t count = 0;
  for (int y = 0; y < dims[1]; ++y) {
    for (int x = 0; x < dims[0]; ++x) {
      const auto* px = static_cast<unsigned char*>(img->GetScalarPointer(x, y, 0));
      if (comps >= 3 && std::abs(px[0] - r) < 40 && std::abs(px[1] - g) < 40 &&
          std::abs(px[2] - b) < 40) {
        ++count;
      }
    }
  }
  return count;
}

TEST(XYChart, LogLogPanelDrawsItsCurves) {
  const auto file = std::filesystem::temp_directory_path() / "drumlab-xy-chart-test.png";
  render::XYPanel panel{
      "error against run time", "wall s per simulated s", "error", {}, true, true};
  // First series colour: (31, 119, 180); values over several decades, one not drawable (<= 0).
  panel.series.push_back({"dt_factor", {0.5, 1.0, 3.0, 10.0, 40.0}, {3e-2, 1e-2, 1e-3, 0.0, 1e-5}});
  panel.series.push_back({"Pareto front", {0.5, 3.0}, {3e-2, 1e-3}, true});
  render::write_xy_charts({panel}, file, 600, 400);
  ASSERT_TRUE(std::filesystem::exists(file));
  // A 2-pixel line across most of the plot area: far more than the legend's sample alone.
  EXPECT_GT(pixels_near(file, 31, 119, 180), 400u);
  std::filesystem::remove(file);
  EXPECT_THROW(render::write_xy_charts({}, file), std::invalid_argument);
}

}  // namespace
}  // namespace drumlab
