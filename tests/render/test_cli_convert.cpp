// `drumlab convert SERIES.h5 --vtu DIR`: an HDF5 series as a VTU/PVD series. The oracle is the
// run's own VTU writer: a run writing --h5 and --vtu together, converted afterwards, gives the
// same particles and arrays bit for bit; a wet series gains the bond graph as lines; bad input
// exits 2 with one line.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <fstream>
#include <sstream>

#include "engine/io/h5_series.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::filesystem::path& file) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

std::size_t entries(const std::filesystem::path& pvd) {
  std::ifstream in(pvd);
  std::stringstream s;
  s << in.rdbuf();
  std::size_t n = 0;
  for (auto at = s.str().find("<DataSet"); at != std::string::npos;
       at = s.str().find("<DataSet", at + 1)) {
    ++n;
  }
  return n;
}

void expect_same_array(vtkUnstructuredGrid* a, vtkUnstructuredGrid* b, const char* name) {
  vtkDataArray* x = a->GetPointData()->GetArray(name);
  vtkDataArray* y = b->GetPointData()->GetArray(name);
  ASSERT_NE(x, nullptr) << name;
  ASSERT_NE(y, nullptr) << name;
  ASSERT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples()) << name;
  ASSERT_EQ(x->GetNumberOfComponents(), y->GetNumberOfComponents()) << name;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i) {
    for (int c = 0; c < x->GetNumberOfComponents(); ++c) {
      ASSERT_EQ(x->GetComponent(i, c), y->GetComponent(i, c)) << name << " tuple " << i;
    }
  }
}

TEST(CliConvert, SeriesGivesTheRunsOwnVtuBitForBit) {
  TempDir dir("cli-convert");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const auto h5 = dir.path() / "s.h5";
  const auto run_vtu = dir.path() / "run_vtu";
  const auto r = run_cli("run " + scene + " --steps 40 --every 10 --h5 " + h5.string() + " --vtu " +
                         run_vtu.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto out = dir.path() / "converted";
  const auto c = run_cli("convert " + h5.string() + " --vtu " + out.string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_EQ(entries(out / "particles.pvd"), 5u);
  EXPECT_FALSE(std::filesystem::exists(out / "bonds.pvd"));  // a dry scene has no bond graph
  for (int k : {0, 4}) {
    const std::string name = fmt::format("particles_{:06d}.vtu", k);
    const auto ran = read_vtu(run_vtu / name);
    const auto converted = read_vtu(out / name);
    ASSERT_EQ(converted->GetNumberOfPoints(), 250);
    for (vtkIdType i = 0; i < 250; ++i) {
      for (int d = 0; d < 3; ++d) {
        ASSERT_EQ(ran->GetPoint(i)[d], converted->GetPoint(i)[d]) << "point " << i;
      }
    }
    for (const char* a : {"id", "radius", "size_class", "velocity", "speed", "angular_velocity"}) {
      expect_same_array(ran, converted, a);
    }
  }
}

TEST(CliConvert, WetSeriesGainsTheBondGraphAndAgglomerates) {
  TempDir dir("cli-convert-wet");
  const std::string scene = dir.write("wet.toml", wet_output_scene_text()).string();
  const auto h5 = dir.path() / "wet.h5";
  const auto r = run_cli("run " + scene + " --steps 30 --every 10 --h5 " + h5.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto out = dir.path() / "vtu";
  const auto c = run_cli("convert " + h5.string() + " --vtu " + out.string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_EQ(entries(out / "bonds.pvd"), 4u);
  const SeriesFrame f = read_series_frame(h5, 3);
  ASSERT_GT(f.bonds.size(), 0u);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((out / "bonds_000003.vtp").c_str());
  reader->Update();
  vtkPolyData* bonds = reader->GetOutput();
  ASSERT_EQ(bonds->GetNumberOfLines(), static_cast<vtkIdType>(f.bonds.size()));
  vtkDataArray* volume = bonds->GetCellData()->GetArray("bridge_volume");
  vtkDataArray* id_a = bonds->GetCellData()->GetArray("id_a");
  ASSERT_NE(volume, nullptr);
  ASSERT_NE(id_a, nullptr);
  for (std::size_t k = 0; k < f.bonds.size(); ++k) {
    EXPECT_EQ(volume->GetComponent(static_cast<vtkIdType>(k), 0), f.bonds[k].volume);
    EXPECT_EQ(id_a->GetComponent(static_cast<vtkIdType>(k), 0), f.id[f.bonds[k].i]);
  }
  const auto particles = read_vtu(out / "particles_000003.vtu");
  vtkDataArray* label = particles->GetPointData()->GetArray("agglomerate_id");
  ASSERT_NE(label, nullptr);
  for (std::size_t i = 0; i < f.id.size(); ++i) {
    EXPECT_EQ(label->GetComponent(static_cast<vtkIdType>(i), 0), f.agglomerate_id[i]);
  }
  EXPECT_NE(particles->GetPointData()->GetArray("liquid_volume"), nullptr);
}

TEST(CliConvert, BadInputExitsTwoWithOneLine) {
  TempDir dir("cli-convert-bad");
  const auto missing = run_cli("convert " + (dir.path() / "none.h5").string() + " --vtu " +
                               (dir.path() / "out").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_EQ(std::count(missing.output.begin(), missing.output.end(), '\n'), 1) << missing.output;
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const auto h5 = dir.path() / "s.h5";
  ASSERT_EQ(run_cli("run " + scene + " --steps 10 --every 10 --h5 " + h5.string()).exit_code, 0);
  const auto blocked = dir.write("file", "not a directory");
  const auto unwritable = run_cli("convert " + h5.string() + " --vtu " + blocked.string());
  EXPECT_EQ(unwritable.exit_code, 2) << unwritable.output;
  EXPECT_NE(unwritable.output.find(blocked.string()), std::string::npos) << unwritable.output;
}

}  // namespace
}  // namespace drumlab::test
