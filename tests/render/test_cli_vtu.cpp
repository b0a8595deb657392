// `drumlab run SCENE --vtu DIR --every K` end to end: one particles_NNNNNN.vtu per scheduled frame,
// listed in particles.pvd, plus drum, contacts and grid series on request; bad paths exit 2.
#include <gtest/gtest.h>

#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUtilities.h>

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
