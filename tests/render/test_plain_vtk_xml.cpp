// engine/io/paraview/xml_writer (VTK's XML formats without VTK, for drumlab-mpi) against VTK's
// own writers: the same dataset written both ways and read back with VTK's reader must give the
// same points, cells, arrays (names, types, components, every value bit for bit) and active
// attributes.
#include <gtest/gtest.h>

#include <filesystem>

#include "engine/analysis/agglomerates.hpp"
#include "engine/io/paraview/frame_datasets.hpp"
#include "engine/io/paraview/wall_datasets.hpp"
#include "engine/io/paraview/xml_writer.hpp"
#include "render/vtk_datasets.hpp"
#include "render/vtk_files.hpp"
#include "tests/render/vtk_compare.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

/// `d` written by VTK and by the plain writer reads back the same.
void expect_same_files(const paraview::DataSet& d, const TempDir& dir, const std::string& name) {
  const std::string ext = d.cells == paraview::CellKind::vertices ? ".vtu" : ".vtp";
  const auto by_vtk = dir.path() / (name + "_vtk" + ext);
  const auto plain = dir.path() / (name + "_plain" + ext);
  render::write_vtk_xml(render::to_vtk(d), by_vtk);
  paraview::write_xml_file(d, plain);
  const auto a = read_back(by_vtk);
  const auto b = read_back(plain);
  ASSERT_NE(a, nullptr) << by_vtk;
  ASSERT_EQ(a->GetNumberOfPoints(), static_cast<vtkIdType>(d.points.size()));
  ASSERT_EQ(a->GetNumberOfCells(), static_cast<vtkIdType>(d.cell_count()));
  SCOPED_TRACE(name);
  expect_same_datasets(a, b);
}

TEST(PlainVtkXml, DryFrameReadsBackAsVtksOwn) {
  TempDir dir("plain-xml-dry");
  auto sim = settled_simulation(output_scene(), 300);
  const paraview::DataSet particles = paraview::particles(*sim);
  ASSERT_EQ(particles.point_data.size(), std::size(paraview::kParticleArrays));
  expect_same_files(particles, dir, "particles");
  expect_same_files(paraview::drum(*sim), dir, "drum");
  const paraview::DataSet contacts = paraview::contacts(*sim);
  ASSERT_GT(contacts.cell_count(), 0u);
  expect_same_files(contacts, dir, "contacts");
}

TEST(PlainVtkXml, TriangleWallsReadBackAsVtksOwn) {
  TempDir dir("plain-xml-walls");
  SmallDrumText t;
  t.wall = "friction = 0.5\n[[wall.lifters]]\ncount = 2\nheight = 0.02\nshape = \"angled\"";
  const std::vector<WallMesh> meshes = build_wall_meshes(parse_scene(t.text(), "walls"));
  const paraview::DataSet walls = paraview::walls(meshes, 0.7);
  ASSERT_EQ(walls.cell_count(), meshes[0].mesh.size());
  expect_same_files(walls, dir, "walls");
}

TEST(PlainVtkXml, WetFrameAndBondsReadBackAsVtksOwn) {
  TempDir dir("plain-xml-wet");
  auto sim = settled_simulation(parse_scene(wet_output_scene_text(), "wet"), 300);
  const paraview::DataSet particles = paraview::particles(*sim, {GranuleMethod::components});
  ASSERT_EQ(particles.point_data.size(), std::size(paraview::kParticleArrays) + 2);
  expect_same_files(particles, dir, "particles");
  expect_same_files(paraview::contacts(*sim), dir, "contacts");
  // A series frame with its bond graph, as `drumlab convert` reads it.
  const Particles& p = sim->particles();
  SeriesFrame frame;
  frame.time = sim->time();
  frame.position = p.position;
  frame.velocity = p.velocity;
  frame.omega = p.omega;
  frame.radius = p.radius;
  frame.id = p.id;
  frame.size_class = p.size_class;
  frame.has_bonds = true;
  frame.film.assign(p.size(), 1e-12);
  frame.agglomerate_id = agglomerate_labels(*sim, {GranuleMethod::components});
  sim->bonds(frame.bonds);
  ASSERT_GT(frame.bonds.size(), 0u);
  expect_same_files(paraview::particles(frame), dir, "frame_particles");
  expect_same_files(paraview::bonds(frame), dir, "frame_bonds");
}

TEST(PlainVtkXml, EmptyDatasetsReadBack) {
  TempDir dir("plain-xml-empty");
  paraview::DataSet none;
  expect_same_files(none, dir, "no_particles");
  paraview::DataSet lines;
  lines.cells = paraview::CellKind::lines;
  lines.cell_data.push_back(paraview::make_array("force", std::vector<double>{}, 3));
  expect_same_files(lines, dir, "no_lines");
}

TEST(PlainVtkXml, UnwritablePathIsAnInputErrorAndLeavesNoFile) {
  TempDir dir("plain-xml-bad");
  const auto target = dir.path() / "missing" / "p.vtu";
  EXPECT_THROW(paraview::write_xml_file(paraview::DataSet{}, target), InputError);
  EXPECT_FALSE(std::filesystem::exists(target));
}

}  // namespace
}  // namespace drumlab::test
