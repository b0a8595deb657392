// Agglomerates in the pictures and the VTU: a wet scene's particle VTU has agglomerate_id (the
// engine's labels) and liquid_volume, its contacts VTP the bridges' volume and force; a dry scene
// has none of them; `--color-by agglomerate` paints a particle alone grey and the members of an
// agglomerate in one palette colour, at the particle's projected centre.
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <cstdlib>
#include "engine/analysis/agglomerates.hpp"

#include "render/drum_view.hpp"
#include "render/frame_writer.hpp"
#include "render/offscreen_context.hpp"
#include "render/vtk_datasets.hpp"
#include "tests/render/render_test_helpers.hpp"

namespace drumlab::test {
namespace {

/// Two touching pairs and one particle alone, with pendular bridges: after one step each pair is
/// bridged.
std::unique_ptr<Simulation> wet_pairs(bool wet) {
  SceneConfig scene = small_drum_scene(0.01);
  scene.liquid.enabled = wet;
  scene.liquid.surface_tension = scene.liquid.wall_surface_tension = 0.072;
  scene.liquid.bridge_volume = 1e-9;
  Particles p;
  // Off the cap's spokes (every 60 degrees from the x axis), which are drawn over the particles.
  p.add(Vec3(-0.06, 0.025, 0.025), 0.01, 2500.0);
  p.add(Vec3(-0.0401, 0.025, 0.025), 0.01, 2500.0);  // overlaps the first by 0.1 mm
  p.add(Vec3(0.06, 0.025, 0.025), 0.01, 2500.0);
  p.add(Vec3(0.0799, 0.025, 0.025), 0.01, 2500.0);
  p.add(Vec3(0.0, -0.09, 0.025), 0.01, 2500.0);  // alone
  auto sim = std::make_unique<Simulation>(scene, std::move(p));
  sim->advance(1);
  return sim;
}

TEST(AgglomerateColors, VtuArraysAndColoursFollowTheEngineLabels) {
  const auto sim = wet_pairs(true);
  std::vector<Bond> bonds;
  sim->bonds(bonds);
  ASSERT_EQ(bonds.size(), 2u);
  const std::vector<std::uint32_t> label = agglomerate_labels(*sim, {GranuleMethod::components});
  const auto grid = render::particles_dataset(*sim, {GranuleMethod::components});
  vtkDataArray* vtu = grid->GetPointData()->GetArray("agglomerate_id");
  ASSERT_NE(vtu, nullptr);
  ASSERT_NE(grid->GetPointData()->GetArray("liquid_volume"), nullptr);
  for (std::size_t i = 0; i < label.size(); ++i) {
    EXPECT_EQ(vtu->GetTuple1(static_cast<vtkIdType>(i)), label[i]) << i;
  }
  const auto contacts = render::contacts_dataset(*sim);
  vtkDataArray* volume = contacts->GetCellData()->GetArray("bridge_volume");
  vtkDataArray* force = contacts->GetCellData()->GetArray("bridge_force");
  ASSERT_NE(volume, nullptr);
  ASSERT_NE(force, nullptr);
  ASSERT_EQ(volume->GetNumberOfTuples(), 2);
  for (vtkIdType k = 0; k < 2; ++k) {
    EXPECT_EQ(volume->GetTuple1(k), 1e-9);
    EXPECT_GT(force->GetTuple1(k), 0.0);
  }

  const std::vector<double> values = render::particle_color_values(
      *sim, render::ColorBy::agglomerate, {GranuleMethod::components});
  const Particles& q = sim->particles();
  std::vector<double> by_id(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) by_id[q.id[i]] = values[i];
  EXPECT_EQ(by_id[4], 0.0);  // alone: grey
  EXPECT_EQ(by_id[0], by_id[1]);
  EXPECT_EQ(by_id[2], by_id[3]);
  EXPECT_EQ(by_id[0], 1.0 + 0.0);  // agglomerate id 0 (smallest member): colour 1
  EXPECT_EQ(by_id[2], 1.0 + 2.0);  // agglomerate id 2: colour 3

  render::ViewOptions opt;
  opt.width = 320;
  opt.height = 240;
  opt.color_by = render::ColorBy::agglomerate;
  opt.granule = {GranuleMethod::components};
  render::OffscreenContext context(opt.width, opt.height);
  render::DrumView view(opt, context);
  const render::Image img = view.render(*sim);
  if (std::getenv("DRUMLAB_TEST_SAVE") != nullptr) render::write_png(img, "/tmp/agglomerates.png");
  const auto grey = view.legend_color(0.0);
  EXPECT_NEAR(grey[0], grey[1], 0.05);  // grey: equal channels
  EXPECT_NEAR(grey[1], grey[2], 0.05);
  EXPECT_NE(view.legend_color(1.0), view.legend_color(3.0));
  for (std::size_t i = 0; i < q.size(); ++i) {
    const auto c = view.project(q.position[i]);
    const auto expected = view.legend_color(values[i]);
    const double rgb[3] = {expected[0], expected[1], expected[2]};
    EXPECT_LE(test::color_distance(img, static_cast<int>(c[0]), static_cast<int>(c[1]), rgb), 40)
        << "particle id " << q.id[i];
  }
}

TEST(AgglomerateColors, DrySceneOutputsHaveNoAgglomerateArrays) {
  const auto sim = wet_pairs(false);
  const auto grid = render::particles_dataset(*sim);
  EXPECT_EQ(grid->GetPointData()->GetNumberOfArrays(),
            static_cast<int>(std::size(render::kParticleArrays)));
  EXPECT_EQ(grid->GetPointData()->GetArray("agglomerate_id"), nullptr);
  const auto contacts = render::contacts_dataset(*sim);
  EXPECT_EQ(contacts->GetCellData()->GetArray("bridge_volume"), nullptr);
  EXPECT_EQ(contacts->GetCellData()->GetNumberOfArrays(), 4);
}

}  // namespace
}  // namespace drumlab::test
