// `drumlab run SCENE --vtu DIR --every K` end to end: one particles_NNNNNN.vtu per scheduled frame,
// listed in particles.pvd, plus drum, contacts and grid series on request, and the triangle walls
// of a scene with meshes (walls_NNNNNN.vtp at the frame's drum angle); bad paths exit 2.
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUtilities.h>
#include <Eigen/Geometry>

#include "engine/mesh/wall_meshes.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

int pvd_entries(const std::filesystem::path& pvd) {
  vtkXMLDataElement* root = vtkXMLUtilities::ReadElementFromFile(pvd.c_str());
  if (root == nullptr) return -1;
  vtkXMLDataElement* c = root->FindNestedElementWithName("Collection");
  const int n = c ? c->GetNumberOfNestedElements() : -1;
  root->Delete();
  return n;
}

TEST(CliVtu, RunWritesOneVtuPerFrameAndCollections) {
  TempDir dir("cli-vtu");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const auto out = dir.path() / "vtu";
  const auto r = run_cli("run " + scene + " --steps 40 --every 10 --vtu " + out.string() +
                         " --contacts-vtk --grid-vtk");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* series : {"particles", "drum", "contacts", "grid"}) {
    EXPECT_EQ(pvd_entries(out / (std::string(series) + ".pvd")), 5) << series;
  }
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((out / "particles_000004.vtu").c_str());
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 250);
  for (const auto& e : std::filesystem::directory_iterator(out)) {
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
  }
}

vtkSmartPointer<vtkPolyData> read_vtp(const std::filesystem::path& file) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

/// The pvd's file attribute of each DataSet entry, in order.
std::vector<std::string> pvd_files(const std::filesystem::path& pvd) {
  std::vector<std::string> files;
  vtkXMLDataElement* root = vtkXMLUtilities::ReadElementFromFile(pvd.c_str());
  if (root == nullptr) return files;
  if (vtkXMLDataElement* c = root->FindNestedElementWithName("Collection")) {
    for (int k = 0; k < c->GetNumberOfNestedElements(); ++k) {
      files.emplace_back(c->GetNestedElement(k)->GetAttribute("file"));
    }
  }
  root->Delete();
  return files;
}

TEST(CliVtu, TriangleWallsAreWrittenBesideEachFrameAtItsDrumAngle) {
  TempDir dir("cli-vtu-walls");
  SmallDrumText t;
  t.omega = "20.0";
  t.wall = "friction = 0.5\n[[wall.lifters]]\ncount = 3\nheight = 0.02";
  t.fill = "count = 100\nsettle_time = 0.0";
  const auto scene_file = dir.write("lifters.toml", t.text());
  const auto out = dir.path() / "vtu";
  const auto r =
      run_cli("run " + scene_file.string() + " --steps 40 --every 10 --vtu " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<std::string> files = pvd_files(out / "walls.pvd");
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(files[4], "walls_000004.vtp");
  const std::vector<WallMesh> built = build_wall_meshes(load_scene(scene_file));
  ASSERT_EQ(built.size(), 1u);
  const TriangleMesh& mesh = built[0].mesh;
  ASSERT_EQ(mesh.size(), 36u);  // three boxes
  for (const int frame : {0, 4}) {
    const auto walls = read_vtp(out / files[static_cast<std::size_t>(frame)]);
    ASSERT_EQ(walls->GetNumberOfPolys(), 36) << frame;
    ASSERT_EQ(walls->GetNumberOfPoints(), static_cast<vtkIdType>(mesh.vertices.size()));
    vtkDataArray* patch = walls->GetCellData()->GetArray("patch");
    vtkDataArray* which = walls->GetCellData()->GetArray("mesh");
    ASSERT_NE(patch, nullptr);
    ASSERT_NE(which, nullptr);
    for (vtkIdType c = 0; c < 36; ++c) {
      EXPECT_EQ(patch->GetTuple1(c), mesh.patch[static_cast<std::size_t>(c)]);
      EXPECT_EQ(which->GetTuple1(c), 0.0);
    }
    // The drum's angle of the frame, as the analytic drum beside it has it; turned by then.
    const auto drum = read_vtp(out / ("drum_00000" + std::to_string(frame) + ".vtp"));
    const double angle = drum->GetFieldData()->GetArray("drum_angle")->GetTuple1(0);
    EXPECT_EQ(walls->GetFieldData()->GetArray("drum_angle")->GetTuple1(0), angle);
    if (frame == 4) {
      EXPECT_GT(angle, 1e-3);  // 40 steps at 20 rad/s
    }
    const Eigen::AngleAxisd turn(angle, Vec3::UnitZ());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const Vec3 want = turn * mesh.vertices[v];
      double got[3];
      walls->GetPoint(static_cast<vtkIdType>(v), got);
      EXPECT_LT((Vec3(got[0], got[1], got[2]) - want).norm(), 1e-12) << frame << " " << v;
    }
    // The triangles: each cell's corners are the mesh's, in its order.
    vtkNew<vtkIdList> ids;
    walls->GetCellPoints(7, ids);
    ASSERT_EQ(ids->GetNumberOfIds(), 3);
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(ids->GetId(k), mesh.triangles[7][static_cast<std::size_t>(k)]);
  }
}

TEST(CliH5, XdmfSidecarIsWellFormedXdmf3) {
  TempDir dir("cli-xdmf");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const auto r =
      run_cli("run " + scene + " --steps 30 --every 10 --h5 " + (dir.path() / "s.h5").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  vtkXMLDataElement* root = vtkXMLUtilities::ReadElementFromFile((dir.path() / "s.xdmf").c_str());
  ASSERT_NE(root, nullptr) << "not well-formed XML";
  EXPECT_STREQ(root->GetName(), "Xdmf");
  EXPECT_STREQ(root->GetAttribute("Version"), "3.0");
  vtkXMLDataElement* domain = root->FindNestedElementWithName("Domain");
  ASSERT_NE(domain, nullptr);
  vtkXMLDataElement* series = domain->FindNestedElementWithName("Grid");
  ASSERT_NE(series, nullptr);
  EXPECT_STREQ(series->GetAttribute("CollectionType"), "Temporal");
  ASSERT_EQ(series->GetNumberOfNestedElements(), 4);
  for (int k = 0; k < 4; ++k) {
    vtkXMLDataElement* grid = series->GetNestedElement(k);
    vtkXMLDataElement* topology = grid->FindNestedElementWithName("Topology");
    ASSERT_NE(topology, nullptr);
    EXPECT_STREQ(topology->GetAttribute("TopologyType"), "Polyvertex");
    EXPECT_STREQ(topology->GetAttribute("NumberOfElements"), "250");
    EXPECT_NE(grid->FindNestedElementWithName("Geometry"), nullptr);
    EXPECT_NE(grid->FindNestedElementWithName("Time"), nullptr);
  }
  root->Delete();
}

TEST(CliBinary, LoadsOnlyTheSerialHdf5) {
  // VTK links libhdf5_serial; a second HDF5 (the OpenMPI build pkg-config points at) would clash.
  FILE* pipe = ::popen((std::string("ldd ") + DRUMLAB_CLI).c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  ASSERT_EQ(::pclose(pipe), 0) << out;
  EXPECT_NE(out.find("libhdf5_serial.so"), std::string::npos) << out;
  EXPECT_EQ(out.find("libhdf5_openmpi"), std::string::npos) << out;
  EXPECT_EQ(out.find("libhdf5.so"), std::string::npos) << out;
}

TEST(CliVtu, BadPathOrMissingVtuStopsWithExitCode2) {
  TempDir dir("cli-vtu-bad");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const auto blocker = dir.write("plain", "x");
  for (const std::string& args : {"--vtu " + (blocker / "vtu").string(), std::string("--grid-vtk"),
                                  std::string("--contacts-vtk")}) {
    const auto r = run_cli("run " + scene + " --steps 20 " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("drumlab: error: "), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace drumlab::test
