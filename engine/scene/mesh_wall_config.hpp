#pragma once
// [[wall.mesh]] and [[wall.lifters]]: walls made of triangles beside the analytic drum (lifters,
// baffles, inserts; engine/mesh/). Plain data as read from the scene; the meshes themselves are
// built by engine/mesh/mesh_walls.hpp.
#include <filesystem>
#include <vector>

#include "engine/types.hpp"

namespace drumlab {

/// The wall law's material of a mesh: [wall]'s, with any of these keys set in the mesh's table.
struct MeshMaterial {
  double youngs_modulus = 0.0;
  double poisson_ratio = 0.0;
  double restitution = 0.0;
  double friction = 0.0;
  double rolling_friction = 0.0;

  friend bool operator==(const MeshMaterial&, const MeshMaterial&) = default;
};

/// Where a mesh lives: turning with the drum (lifters, inserts fixed to the shell) or standing in
/// the lab (a scraper, a plough); both in the drum's coordinates (axis z, the drum at rest).
enum class MeshAttach { drum, lab };

/// [[wall.mesh]]: an STL file, moved by x -> R (scale x) + offset, R the rotation by
/// rotation_deg[0] about x, then [1] about y, then [2] about z.
struct MeshWallConfig {
  std::filesystem::path file;  ///< resolved against the scene's folder
  double scale = 1.0;
  Vec3 offset = Vec3::Zero();        ///< m
  Vec3 rotation_deg = Vec3::Zero();  ///< degrees
  MeshAttach attach = MeshAttach::drum;
  double smooth_angle_deg = 20.0;  ///< edges bent by at most this join one smooth patch
  bool closed = false;             ///< require a closed, consistently oriented surface
  MeshMaterial material;

  friend bool operator==(const MeshWallConfig&, const MeshWallConfig&) = default;
};

enum class LifterKind { straight, angled };

/// [[wall.lifters]]: generated flights (engine/mesh/lifters.hpp), turning with the drum.
struct LifterWallConfig {
  int count = 4;
  double height = 0.0;     ///< m, radial
  double length = 0.0;     ///< m, axial; 0: the drum's depth
  double thickness = 0.0;  ///< m; 0: height / 8
  LifterKind shape = LifterKind::straight;
  double angle_deg = 90.0;  ///< angled: the tip's bend from the inward radial
  double tip = 0.0;         ///< angled: the tip's length, m; 0: height / 2
  double phase_deg = 0.0;   ///< the first lifter's angle in the drum's frame
  MeshMaterial material;

  friend bool operator==(const LifterWallConfig&, const LifterWallConfig&) = default;
};

}  // namespace drumlab
