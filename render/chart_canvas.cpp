#include "render/chart_canvas.hpp"

#include <stdexcept>

#include <vtkChartXY.h>
#include <vtkContextActor.h>
#include <vtkContextScene.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkRenderer.h>

#include "render/frame_writer.hpp"
#include "render/offscreen_context.hpp"

namespace drumlab::render {

void write_chart_panels(std::size_t count,
                        const std::function<void(vtkChartXY*, std::size_t)>& fill,
                        const std::filesystem::path& file, int width, int height) {
  OffscreenContext context(width, height);  // outlives every VTK object below
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  window->SetOwnContext(false);
  window->SetSize(width, height);
  window->SetIsCurrent(true);
  window->SetReadyForRendering(true);
  window->SetMultiSamples(0);
  if (!window->InitializeFromCurrentContext()) {
    throw std::runtime_error("render: VTK could not use the OSMesa context");
  }
  // What vtkContextView does (ViewsContext2D is not linked): a context actor in a renderer.
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  window->AddRenderer(renderer);
  vtkNew<vtkContextActor> actor;
  actor->GetScene()->SetRenderer(renderer);
  renderer->AddActor(actor);
  const float w = static_cast<float>(width) / static_cast<float>(count);
  for (std::size_t k = 0; k < count; ++k) {
    vtkNew<vtkChartXY> chart;
    chart->SetAutoSize(false);
    chart->SetSize(vtkRectf(static_cast<float>(k) * w, 0.0f, w, static_cast<float>(height)));
    fill(chart, k);
    actor->GetScene()->AddItem(chart);
  }
  window->Render();
  write_png(context.read_image(), file);
}

}  // namespace drumlab::render
