// Triangle meshes and STL files (engine/mesh/): welding, normals, smooth patches by dihedral
// angle, closedness; binary and ASCII STL read back; every damaged file one InputError naming
// the file and what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include <fmt/format.h>

#include "engine/mesh/stl_file.hpp"
#include "engine/mesh/triangle_mesh.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

/// A closed, outward-oriented cube of side 2 a about the origin (12 triangles).
std::vector<std::array<Vec3, 3>> cube(double a) {
  std::vector<std::array<Vec3, 3>> out;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      Vec3 n = Vec3::Zero(), u = Vec3::Zero(), v = Vec3::Zero();
      n[axis] = side;
      u[(axis + 1) % 3] = 1.0;
      v[(axis + 2) % 3] = 1.0;
      if (side < 0.0) std::swap(u, v);  // u x v along n
      const Vec3 c = a * n;
      const Vec3 p0 = c - a * u - a * v, p1 = c + a * u - a * v, p2 = c + a * u + a * v,
                 p3 = c - a * u + a * v;
      out.push_back({p0, p1, p2});
      out.push_back({p0, p2, p3});
    }
  }
  return out;
}

/// A closed prism of `facets` sides about z (radius 1, height 1): the mesh cylinder.
std::vector<std::array<Vec3, 3>> prism(int facets) {
  std::vector<std::array<Vec3, 3>> out;
  const auto at = [&](int k, double z) {
    const double t = 2.0 * std::numbers::pi * (k % facets) / facets;  // the seam welds
    return Vec3(std::cos(t), std::sin(t), z);
  };
  for (int k = 0; k < facets; ++k) {  // the mantle, normals outward
    out.push_back({at(k, 0.0), at(k + 1, 0.0), at(k + 1, 1.0)});
    out.push_back({at(k, 0.0), at(k + 1, 1.0), at(k, 1.0)});
    out.push_back({Vec3(0.0, 0.0, 0.0), at(k + 1, 0.0), at(k, 0.0)});  // bottom, normal -z
    out.push_back({Vec3(0.0, 0.0, 1.0), at(k, 1.0), at(k + 1, 1.0)});  // top, normal +z
  }
  return out;
}

TEST(TriangleMesh, WeldsCornersAndFindsPatchesByDihedralAngle) {
  const TriangleMesh box = make_mesh(cube(0.5), 10.0 * std::numbers::pi / 180.0, "cube");
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(box.patches, 6u);  // each face's two triangles, the 90-degree edges sharp
  EXPECT_TRUE(is_closed(box));
  for (std::size_t t = 0; t < box.size(); ++t) {  // outward: the normal points away from the centre
    EXPECT_GT(box.normals[t].dot(box.corner(t, 0)), 0.0);
  }
  // A 24-facet cylinder: 15 degrees between facets; one mantle patch at 20, 24 at 10.
  TriangleMesh can = make_mesh(prism(24), 20.0 * std::numbers::pi / 180.0, "can");
  EXPECT_TRUE(is_closed(can));
  EXPECT_EQ(can.patches, 3u);  // mantle, bottom, top
  assign_patches(can, 10.0 * std::numbers::pi / 180.0);
  EXPECT_EQ(can.patches, 26u);
  // Open and mis-oriented meshes are not closed, with the edge named.
  std::vector<std::array<Vec3, 3>> open = cube(0.5);
  open.pop_back();
  std::string why;
  EXPECT_FALSE(is_closed(make_mesh(open, 0.1, "open"), &why));
  EXPECT_NE(why.find("belongs to 1 triangle"), std::string::npos) << why;
  std::vector<std::array<Vec3, 3>> flipped = cube(0.5);
  std::swap(flipped[0][1], flipped[0][2]);
  EXPECT_FALSE(is_closed(make_mesh(flipped, 0.1, "flipped"), &why));
  EXPECT_NE(why.find("inconsistent orientation"), std::string::npos) << why;
}

TEST(TriangleMesh, BadTrianglesAreOneLineNamingTheFileAndTheTriangle) {
  std::vector<std::array<Vec3, 3>> t = cube(0.5);
  t[4][1] = Vec3(NAN, 0.0, 0.0);
  try {
    make_mesh(t, 0.1, "lifter.stl");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "lifter.stl: triangle 5 has a non-finite vertex coordinate");
  }
  t = cube(0.5);
  t[2][2] = 0.5 * (t[2][0] + t[2][1]);  // on one line
  try {
    make_mesh(t, 0.1, "lifter.stl");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "lifter.stl: triangle 3 is degenerate (its corners are (nearly) on one line)");
  }
  EXPECT_THROW(make_mesh({}, 0.1, "empty.stl"), InputError);
  TriangleMesh box = make_mesh(cube(0.5), 0.1, "cube");
  EXPECT_THROW(assign_patches(box, -0.1), InputError);
}

TEST(StlFile, BinaryAndAsciiReadBackAndDamagesAreOneLine) {
  TempDir dir("stl");
  const TriangleMesh box = make_mesh(cube(0.25), 0.1, "cube");  // exact in float
  const auto bin = dir.path() / "cube.stl";
  write_stl(box, bin);
  EXPECT_EQ(std::filesystem::file_size(bin), 84u + 50u * 12u);
  const auto back = read_stl(bin);
  ASSERT_EQ(back.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(back[t][static_cast<std::size_t>(k)], box.corner(t, k));
  }
  // ASCII, as CAD exporters write it.
  std::string ascii = "solid part\n";
  for (const auto& tri : cube(0.25)) {
    ascii += "  facet normal 0 0 0\n    outer loop\n";
    for (const Vec3& x : tri) ascii += fmt::format("      vertex {} {} {}\n", x.x(), x.y(), x.z());
    ascii += "    endloop\n  endfacet\n";
  }
  ascii += "endsolid part\n";
  const auto text = dir.write("cube_ascii.stl", ascii);
  EXPECT_EQ(read_stl(text), cube(0.25));

  const auto message = [](const std::filesystem::path& f) {
    try {
      read_stl(f);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(dir.path() / "missing.stl"),
            (dir.path() / "missing.stl").string() + ": cannot open the STL file");
  // A binary file cut short.
  std::filesystem::copy_file(bin, dir.path() / "cut.stl");
  std::filesystem::resize_file(dir.path() / "cut.stl", 84 + 50 * 7 + 13);
  EXPECT_NE(message(dir.path() / "cut.stl").find("needs 684 bytes, the file has 447"),
            std::string::npos)
      << message(dir.path() / "cut.stl");
  // ASCII cut inside a facet, and without its end.
  const auto cut_ascii = dir.write("cut_ascii.stl", ascii.substr(0, ascii.size() / 2));
  EXPECT_NE(message(cut_ascii).find("truncated"), std::string::npos) << message(cut_ascii);
  const auto no_vertex = dir.write("bad_vertex.stl",
                                   "solid x\nfacet normal 0 0 1\nouter loop\n"
                                   "vertex 0 0 zero\n");
  EXPECT_NE(message(no_vertex).find("a vertex without three numbers"), std::string::npos);
  const auto tiny = dir.write("tiny.stl", "abc");
  EXPECT_NE(message(tiny).find("too short for an STL file"), std::string::npos);
  const auto empty = dir.write("empty.stl", "solid x\nendsolid x\n");
  EXPECT_NE(message(empty).find("has no triangle"), std::string::npos);
}

}  // namespace
}  // namespace drumlab::test
