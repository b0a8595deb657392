#include "render/wall_mesh_actors.hpp"

#include <numbers>
#include <span>

#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include "engine/io/paraview/wall_datasets.hpp"
#include "render/palette.hpp"
#include "render/vtk_datasets.hpp"

namespace drumlab::render {

// The actors go with the renderer: removing them here would release their graphics resources
// after the view has finalised its window.
WallMeshActors::~WallMeshActors() = default;

void WallMeshActors::build(const std::vector<WallMesh>& meshes) {
  for (vtkActor* a : actors_) renderer_->RemoveActor(a);
  actors_.clear();
  turns_.clear();
  for (const WallMesh& w : meshes) {
    // The drum-frame triangles at angle 0; the actor's orientation turns them.
    const vtkSmartPointer<vtkDataSet> surface = to_vtk(paraview::walls(std::span(&w, 1), 0.0));
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(vtkPolyData::SafeDownCast(surface));
    mapper->ScalarVisibilityOff();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    vtkProperty* p = actor->GetProperty();
    p->SetColor(kMeshWallColor[0], kMeshWallColor[1], kMeshWallColor[2]);
    p->SetInterpolationToFlat();
    p->SetAmbient(0.25);
    p->SetDiffuse(0.75);
    p->SetSpecular(0.08);
    p->SetSpecularPower(20.0);
    p->BackfaceCullingOff();  // an open mesh (a baffle plate) shows both sides
    renderer_->AddActor(actor);
    actors_.push_back(actor);
    turns_.push_back(w.attach == MeshAttach::drum);
  }
}

void WallMeshActors::update(const FrameSnapshot& s) {
  if (s.meshes != drawn_) {
    drawn_ = s.meshes;
    build(drawn_ ? *drawn_ : std::vector<WallMesh>{});
  }
  const double turn_deg = s.drum_angle * 180.0 / std::numbers::pi;
  for (std::size_t k = 0; k < actors_.size(); ++k) {
    if (turns_[k]) actors_[k]->SetOrientation(0.0, 0.0, turn_deg);
  }
}

void WallMeshActors::set_visibility(bool visible) {
  for (vtkActor* a : actors_) a->SetVisibility(visible);
}

}  // namespace drumlab::render
