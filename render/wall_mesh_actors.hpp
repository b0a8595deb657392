#pragma once
// The triangle walls of a snapshot ([[wall.mesh]], [[wall.lifters]]) in the drum picture: one
// flat-shaded surface per mesh in the walls' metallic colour (kMeshWallColor), those attached to
// the drum turned by its angle each frame, those fixed in the lab standing. A scene without meshes
// adds no actor. The surfaces are built from the snapshot's shared, immutable meshes, never from
// the live Simulation, and again only when the snapshot brings other meshes (a restarted scene).
#include <memory>
#include <vector>

#include <vtkSmartPointer.h>

#include "engine/session/frame_snapshot.hpp"

class vtkActor;
class vtkRenderer;

namespace drumlab::render {

class WallMeshActors {
 public:
  /// Adds its actors to `renderer` (which must outlive it; they stay in it after this is gone).
  explicit WallMeshActors(vtkRenderer* renderer) : renderer_(renderer) {}
  ~WallMeshActors();
  WallMeshActors(const WallMeshActors&) = delete;
  WallMeshActors& operator=(const WallMeshActors&) = delete;

  /// Builds the surfaces if the snapshot's meshes are not those drawn, and turns the attached
  /// ones to the snapshot's drum angle (in the drum's frame: the picture's motion is the
  /// caller's, a user transform on every actor).
  void update(const FrameSnapshot& snapshot);
  void set_visibility(bool visible);
  std::size_t size() const { return actors_.size(); }

 private:
  void build(const std::vector<WallMesh>& meshes);

  vtkRenderer* renderer_;
  std::shared_ptr<const std::vector<WallMesh>> drawn_;  // kept: its address names what is drawn
  std::vector<vtkSmartPointer<vtkActor>> actors_;
  std::vector<bool> turns_;  // attached to the drum
};

}  // namespace drumlab::render
