#pragma once
// The triangle walls ([[wall.mesh]], [[wall.lifters]]) as a ParaView dataset (dataset.hpp): the
// walls_NNNNNN.vtp of a VTU/PVD series, and the surface the renderer draws. Without VTK.
#include <span>

#include "engine/io/paraview/dataset.hpp"
#include "engine/mesh/wall_meshes.hpp"
#include "engine/simulation.hpp"

namespace drumlab::paraview {

/// Every triangle of `meshes` as a polygon, a mesh attached to the drum turned about z by
/// `drum_angle` (rad), one fixed in the lab as it stands. Points: each mesh's welded vertices, mesh
/// after mesh. Cell data: mesh (UInt32, the mesh's index: [[wall.mesh]] in order, then
/// [[wall.lifters]]), patch (UInt32, the smooth patch within its mesh), attach (UInt8: 0 drum,
/// 1 lab). Field data: drum_angle (rad). Active scalars patch.
DataSet walls(std::span<const WallMesh> meshes, double drum_angle);

/// The walls of the simulation at its current drum angle (an empty set without meshes).
DataSet walls(const Simulation& sim);

}  // namespace drumlab::paraview
