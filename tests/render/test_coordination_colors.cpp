// The PNG's colour-by-coordination values are the engine's coordination numbers, the same as the
// VTU's coordination array, also for a contact across periodic ends.
#include <gtest/gtest.h>

#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>

#include "render/drum_view.hpp"
#include "render/vtk_datasets.hpp"
#include "tests/render/render_test_helpers.hpp"

namespace drumlab::test {
namespace {

TEST(CoordinationColors, PngValuesEqualTheVtuArrayAcrossPeriodicEnds) {
  SceneConfig scene = small_drum_scene(0.01);  // H = 0.05 m > 4 r
  scene.drum.ends = DrumEnds::periodic;
  Particles p;
  p.add(Vec3(0.0, 0.0, 0.005), 0.01, 2500.0);
  p.add(Vec3(0.0, 0.0, 0.036), 0.01, 2500.0);  // 19 mm from the first across z = 0: touching
  p.add(Vec3(0.1, 0.0, 0.025), 0.01, 2500.0);
  p.add(Vec3(0.1195, 0.0, 0.025), 0.01, 2500.0);  // overlaps the third by 0.5 mm
  p.add(Vec3(-0.1, 0.0, 0.025), 0.01, 2500.0);    // alone
  const Simulation sim(scene, std::move(p));

  const std::vector<double> png = render::particle_color_values(sim, render::ColorBy::coordination);
  const auto grid = render::particles_dataset(sim);
  vtkDataArray* vtu = grid->GetPointData()->GetArray("coordination");
  ASSERT_NE(vtu, nullptr);
  ASSERT_EQ(vtu->GetNumberOfTuples(), static_cast<vtkIdType>(png.size()));
  for (std::size_t i = 0; i < png.size(); ++i) {
    EXPECT_EQ(png[i], vtu->GetTuple1(static_cast<vtkIdType>(i))) << i;
  }
  // Storage order may differ from insertion order: count by stable id.
  const Particles& q = sim.particles();
  std::vector<double> by_id(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) by_id[q.id[i]] = png[i];
  EXPECT_EQ(by_id, (std::vector<double>{1, 1, 1, 1, 0}));
}

}  // namespace
}  // namespace drumlab::test
