#include "engine/mesh/wall_meshes.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "engine/mesh/lifters.hpp"
#include "engine/mesh/stl_file.hpp"

namespace drumlab {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// Whether some triangle of `m` reaches inside the drum (a corner strictly within the mantle and
/// between the caps, or periodic ends).
bool reaches_inside(const TriangleMesh& m, const DrumConfig& drum) {
  const double r = 0.5 * drum.diameter;
  for (std::size_t t = 0; t < m.size(); ++t) {
    Vec3 centre = Vec3::Zero();
    for (int k = 0; k <= 3; ++k) {
      const Vec3 x = k < 3 ? m.corner(t, k) : centre / 3.0;
      if (k < 3) centre += x;
      const bool radial = x.x() * x.x() + x.y() * x.y() < r * r;
      const bool axial = drum.ends == DrumEnds::periodic || (x.z() > 0.0 && x.z() < drum.depth);
      if (radial && axial) return true;
    }
  }
  return false;
}

WallMesh checked(TriangleMesh mesh, const std::string& key, const SceneConfig& scene, bool closed) {
  std::string why;
  if (closed && !is_closed(mesh, &why)) {
    throw MeshWallError(key, fmt::format("{}: not a closed surface ({}); closed = true needs one",
                                         mesh.source, why));
  }
  if (!reaches_inside(mesh, scene.drum)) {
    throw MeshWallError(key, fmt::format("{}: the mesh lies outside the drum (R = {} m, H = {} "
                                         "m): no triangle reaches inside",
                                         mesh.source, 0.5 * scene.drum.diameter, scene.drum.depth));
  }
  return WallMesh{std::move(mesh), MeshAttach::drum, {}, key};
}

}  // namespace

Eigen::Matrix3d mesh_rotation(const Vec3& angles_deg) {
  return (Eigen::AngleAxisd(angles_deg.z() * kDegree, Vec3::UnitZ()) *
          Eigen::AngleAxisd(angles_deg.y() * kDegree, Vec3::UnitY()) *
          Eigen::AngleAxisd(angles_deg.x() * kDegree, Vec3::UnitX()))
      .toRotationMatrix();
}

std::vector<WallMesh> build_wall_meshes(const SceneConfig& scene) {
  std::vector<WallMesh> out;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshWallConfig& c = scene.meshes[i];
    const std::string key = fmt::format("wall.mesh[{}]", i);
    std::vector<std::array<Vec3, 3>> corners;
    try {
      corners = read_stl(c.file);
      const Eigen::Matrix3d rotation = mesh_rotation(c.rotation_deg);
      for (auto& t : corners) {
        for (Vec3& x : t) x = rotation * (c.scale * x) + c.offset;
      }
      WallMesh w = checked(make_mesh(corners, c.smooth_angle_deg * kDegree, c.file.string()), key,
                           scene, c.closed);
      w.attach = c.attach;
      w.material = c.material;
      out.push_back(std::move(w));
    } catch (const MeshWallError&) {
      throw;
    } catch (const InputError& e) {
      throw MeshWallError(key, e.what());
    }
  }
  for (std::size_t i = 0; i < scene.lifters.size(); ++i) {
    const LifterWallConfig& c = scene.lifters[i];
    const std::string key = fmt::format("wall.lifters[{}]", i);
    LifterSpec spec;
    spec.count = c.count;
    spec.height = c.height;
    spec.length = c.length;
    spec.thickness = c.thickness;
    spec.shape = c.shape == LifterKind::angled ? LifterShape::angled : LifterShape::straight;
    spec.angle = c.angle_deg * kDegree;
    spec.tip = c.tip;
    spec.phase = c.phase_deg * kDegree;
    spec.turn_sign = scene.drum.omega < 0.0 ? -1 : 1;
    try {
      // Lifters: flat faces meeting at right angles, so any smooth angle below 90 degrees splits
      // them into their faces.
      WallMesh w =
          checked(make_mesh(lifter_triangles(spec, 0.5 * scene.drum.diameter, scene.drum.depth),
                            20.0 * kDegree, key),
                  key, scene, true);
      w.material = c.material;
      out.push_back(std::move(w));
    } catch (const MeshWallError&) {
      throw;
    } catch (const InputError& e) {
      std::string reason = e.what();
      // lifter_triangles names "wall.lifters.<key>"; the key here carries the index.
      if (reason.rfind("wall.lifters.", 0) == 0) reason = reason.substr(13);
      throw MeshWallError(key, reason);
    }
  }
  return out;
}

}  // namespace drumlab
