// The VTU/PVD series read back with VTK's XML readers: point count, array names and values equal
// to the engine's (coordination numbers against an independent O(N^2) count), the .pvd lists every
// frame with its time, contacts as lines with positive forces, the drum wall's extent, and the grid
// occupancy summing to the particle count. Bad paths give InputError and leave no file.
#include <gtest/gtest.h>

#include <filesystem>

#include <fmt/format.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUtilities.h>

#include "render/vtk_datasets.hpp"
#include "render/vtk_files.hpp"
#include "render/vtu_series_writer.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/file_size_limit.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

using namespace drumlab::render;

template <class Reader>
auto read_xml(const std::filesystem::path& file) {
  vtkNew<Reader> r;
  r->SetFileName(file.c_str());
  r->Update();
  return vtkSmartPointer<std::remove_pointer_t<decltype(r->GetOutput())>>(r->GetOutput());
}

/// Particle-particle overlaps per particle, by brute force (no periodic ends in this scene).
std::vector<std::uint32_t> brute_coordination(const Particles& p) {
  std::vector<std::uint32_t> c(p.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      if ((p.position[i] - p.position[j]).norm() < p.radius[i] + p.radius[j]) {
        ++c[i];
        ++c[j];
      }
    }
  }
  return c;
}

void expect_vec_array(vtkDataArray* a, const std::vector<Vec3>& v) {
  ASSERT_NE(a, nullptr);
  ASSERT_EQ(a->GetNumberOfComponents(), 3);
  ASSERT_EQ(a->GetNumberOfTuples(), static_cast<vtkIdType>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(a->GetComponent(static_cast<vtkIdType>(i), c), v[i][c]) << a->GetName() << i;
    }
  }
}

TEST(VtuSeries, ParticlesReadBackEqualTheEngine) {
  TempDir dir("vtu-series");
  const SceneConfig scene = output_scene();
  auto sim = settled_simulation(scene, 300);
  VtuSeriesWriter writer(dir.path() / "vtu", VtuSeriesOptions{true, true, {}});
  writer.write_frame(*sim);
  const double t0 = sim->time();
  sim->advance(40);
  writer.write_frame(*sim);
  const Particles& p = sim->particles();
  const std::size_t n = p.size();

  auto grid = read_xml<vtkXMLUnstructuredGridReader>(dir.path() / "vtu" / "particles_000001.vtu");
  ASSERT_EQ(grid->GetNumberOfPoints(), static_cast<vtkIdType>(n));
  EXPECT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(n));
  vtkPointData* pd = grid->GetPointData();
  ASSERT_EQ(pd->GetNumberOfArrays(), 8);
  for (int k = 0; k < 8; ++k) EXPECT_STREQ(pd->GetArrayName(k), kParticleArrays[k]);
  for (std::size_t i = 0; i < n; ++i) {
    double x[3];
    grid->GetPoint(static_cast<vtkIdType>(i), x);
    ASSERT_EQ(Vec3(x[0], x[1], x[2]), p.position[i]) << i;
  }
  expect_vec_array(pd->GetArray("velocity"), p.velocity);
  expect_vec_array(pd->GetArray("angular_velocity"), p.omega);
  expect_vec_array(pd->GetArray("force"), p.force);
  const std::vector<std::uint32_t> coordination = brute_coordination(p);
  std::size_t touching = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<vtkIdType>(i);
    ASSERT_EQ(pd->GetArray("id")->GetTuple1(k), p.id[i]);
    ASSERT_EQ(pd->GetArray("radius")->GetTuple1(k), p.radius[i]);
    ASSERT_EQ(pd->GetArray("size_class")->GetTuple1(k), p.size_class[i]);
    ASSERT_EQ(pd->GetArray("speed")->GetTuple1(k), p.velocity[i].norm());
    ASSERT_EQ(pd->GetArray("coordination")->GetTuple1(k), coordination[i]) << i;
    touching += coordination[i] > 0;
  }
  EXPECT_GT(touching, n / 10) << "a settled bed has contacts";
  EXPECT_EQ(pd->GetArray("id")->GetDataType(), VTK_UNSIGNED_INT);
  EXPECT_EQ(pd->GetArray("size_class")->GetDataType(), VTK_UNSIGNED_CHAR);

  // The collection: two frames with their times, files that exist.
  vtkSmartPointer<vtkXMLDataElement> pvd;
  pvd.TakeReference(
      vtkXMLUtilities::ReadElementFromFile((dir.path() / "vtu" / "particles.pvd").c_str()));
  ASSERT_NE(pvd, nullptr);
  EXPECT_STREQ(pvd->GetAttribute("type"), "Collection");
  vtkXMLDataElement* collection = pvd->FindNestedElementWithName("Collection");
  ASSERT_NE(collection, nullptr);
  ASSERT_EQ(collection->GetNumberOfNestedElements(), 2);
  const double times[2] = {t0, sim->time()};
  for (int k = 0; k < 2; ++k) {
    vtkXMLDataElement* e = collection->GetNestedElement(k);
    double t = -1.0;
    e->GetScalarAttribute("timestep", t);
    EXPECT_EQ(t, times[k]);
    EXPECT_EQ(e->GetAttribute("file"), fmt::format("particles_{:06d}.vtu", k));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "vtu" / e->GetAttribute("file")));
  }

  // Contacts: one line per overlapping pair, positive force magnitudes.
  auto contacts = read_xml<vtkXMLPolyDataReader>(dir.path() / "vtu" / "contacts_000001.vtp");
  std::size_t pairs = 0;
  for (std::uint32_t c : coordination) pairs += c;
  EXPECT_EQ(contacts->GetNumberOfLines(), static_cast<vtkIdType>(pairs / 2));
  vtkDataArray* f = contacts->GetCellData()->GetArray("force_magnitude");
  ASSERT_NE(f, nullptr);
  double range[2];
  f->GetRange(range);
  EXPECT_GT(range[0], 0.0);

  // Drum wall: cylinder of radius D/2 from z = 0 to H, 96 quads + 2 caps.
  auto drum = read_xml<vtkXMLPolyDataReader>(dir.path() / "vtu" / "drum_000001.vtp");
  double b[6];
  drum->GetBounds(b);
  const double r = 0.5 * scene.drum.diameter;
  EXPECT_NEAR(b[1] - b[0], 2.0 * r, 1e-3 * r);
  EXPECT_LE(b[1], r * (1.0 + 1e-12));
  EXPECT_DOUBLE_EQ(b[4], 0.0);
  EXPECT_DOUBLE_EQ(b[5], scene.drum.depth);
  EXPECT_EQ(drum->GetNumberOfPolys(), 98);

  // Grid occupancy: every particle in exactly one cell.
  auto image = read_xml<vtkXMLImageDataReader>(dir.path() / "vtu" / "grid_000001.vti");
  vtkDataArray* occupancy = image->GetCellData()->GetArray("particles");
  ASSERT_NE(occupancy, nullptr);
  double total = 0.0;
  for (vtkIdType c = 0; c < occupancy->GetNumberOfTuples(); ++c) total += occupancy->GetTuple1(c);
  EXPECT_EQ(total, static_cast<double>(n));
  EXPECT_GT(image->GetNumberOfCells(), 1);
}

TEST(VtuSeries, BadPathsGiveInputErrorAndLeaveNoFile) {
  TempDir dir("vtu-bad");
  const auto sim = settled_simulation(output_scene(), 5);
  const auto blocker = dir.write("plain-file", "x");
  EXPECT_THROW(VtuSeriesWriter(blocker / "vtu", {}), InputError);
  const auto target = dir.path() / "missing" / "p.vtu";
  EXPECT_THROW(write_vtk_xml(particles_dataset(*sim), target), InputError);
  EXPECT_FALSE(std::filesystem::exists(target));
  // A directory in the way of the final name: the temporary is written, the rename fails.
  std::filesystem::create_directories(dir.path() / "taken.vtu" / "x");
  EXPECT_THROW(write_vtk_xml(particles_dataset(*sim), dir.path() / "taken.vtu"), InputError);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 2);
}

TEST(VtuSeries, FullDiskStopsWithInputErrorAndLeavesNoFile) {
  TempDir dir("vtu-full");
  const auto sim = settled_simulation(output_scene(), 5);
  const auto file = dir.path() / "p.vtu";
  {
    const FileSizeLimit limit(4 * 1024);  // the particles need about 20 kB compressed
    ASSERT_TRUE(limit.ok());
    EXPECT_THROW(write_vtk_xml(particles_dataset(*sim), file), InputError);
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 0);
  write_vtk_xml(particles_dataset(*sim), file);
  EXPECT_TRUE(std::filesystem::exists(file));
}

}  // namespace
}  // namespace drumlab::test
