#pragma once
// A wall as a triangle mesh (lifters, baffles, inserts; issue "Drums as they are built"): welded
// vertices, triangles with their unit normals (right-handed from the vertex order), the edges
// each pair of triangles shares, and the smooth patches: triangles joined across edges whose
// dihedral angle is at most `smooth_angle` (a flat face split into many triangles, or a mesh
// cylinder of many facets, is one patch; a lifter's blade meets the mantle at a sharp edge, so
// they are two). A particle feels one force per patch it touches (patch_contact.hpp).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/types.hpp"

namespace drumlab {

struct TriangleMesh {
  std::vector<Vec3> vertices;                   ///< m, welded (each position once)
  std::vector<std::array<Index, 3>> triangles;  ///< vertex indices, counter-clockwise about normal
  std::vector<Vec3> normals;                    ///< unit normal of each triangle
  std::vector<Index> patch;                     ///< smooth patch of each triangle, 0..patches-1
  Index patches = 0;
  std::string source;  ///< the file (or "lifters") in error messages

  std::size_t size() const { return triangles.size(); }
  const Vec3& corner(std::size_t t, int k) const { return vertices[triangles[t][k]]; }
};

/// Builds a mesh from triangle corners (three points each, as an STL lists them): welds corners
/// at bitwise-equal positions, computes the normals and the patches. Throws InputError naming
/// `source` for a non-finite coordinate or a degenerate triangle (area below 1e-12 of the
/// squared longest edge), with the triangle's number (from 1).
TriangleMesh make_mesh(const std::vector<std::array<Vec3, 3>>& corners, double smooth_angle,
                       const std::string& source);

/// Recomputes `mesh.patch` with another smooth angle (rad, in [0, pi)).
void assign_patches(TriangleMesh& mesh, double smooth_angle);

/// Whether every edge is shared by exactly two triangles that run it in opposite directions
/// (a closed, consistently oriented surface); `why` gets the first offending edge if not.
bool is_closed(const TriangleMesh& mesh, std::string* why = nullptr);

/// The winding number of a closed mesh about p (the solid angles of its triangles seen from p,
/// over 4 pi; Van Oosterom and Strackee's formula): 1 inside an outward-oriented closed mesh, 0
/// outside (p off the surface).
double winding_number(const TriangleMesh& mesh, const Vec3& p);

/// The triangle corners of `mesh` moved by x -> R x + t (scale first: x -> s x).
std::vector<std::array<Vec3, 3>> transformed_corners(const TriangleMesh& mesh, double scale,
                                                     const Eigen::Matrix3d& rotation,
                                                     const Vec3& offset);

}  // namespace drumlab
