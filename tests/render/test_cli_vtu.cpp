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

TEST(CliVtu, BadPathOrMissingVtuStopsWithExitCode2) {
  TempDir dir("cli-vtu-bad");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const auto blocker = dir.write("plain", "x");
  for (const std::string args : {"--vtu " + (blocker / "vtu").string(), std::string("--grid-vtk"),
                                 std::string("--contacts-vtk")}) {
    const auto r = run_cli("run " + scene + " --steps 20 " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("drumlab: error: "), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace drumlab::test
