// A drum whose mantle is a triangle mesh: a cylinder of 96 flat facets (one smooth patch), turning
// with the drum inside a slightly larger analytic mantle, carries the bed to the analytic drum's
// angle of repose (the centre-of-mass angle over the same window of the same run from the same
// particles) within the window's noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "engine/analysis/drum_observables.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/mesh/stl_file.hpp"
#include "engine/simulation.hpp"
#include "tests/small_drum_text.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab {
namespace {

/// The tube of radius r and depth h as n facets (two triangles each), normals inwards.
TriangleMesh tube(double r, double h, int n) {
  std::vector<std::array<Vec3, 3>> t;
  const auto at = [&](int k, double z) {
    const double a = 2.0 * std::numbers::pi * (k % n) / n;
    return Vec3(r * std::cos(a), r * std::sin(a), z);
  };
  for (int k = 0; k < n; ++k) {
    t.push_back({at(k, 0.0), at(k, h), at(k + 1, 0.0)});
    t.push_back({at(k + 1, 0.0), at(k, h), at(k + 1, h)});
  }
  return make_mesh(t, 0.35, "tube");
}

/// The centre-of-mass angle (degrees) sampled every 200 steps over `samples` samples.
std::vector<double> angles(Simulation& sim, int samples) {
  std::vector<double> out;
  for (int k = 0; k < samples; ++k) {
    sim.advance(200);
    out.push_back(measure_drum(sim).com_angle_deg);
  }
  return out;
}

TEST(MeshCylinder, AFacetedMantleGivesTheAnalyticDrumsAngleOfRepose) {
  test::TempDir dir("mesh-cylinder");
  const double inner = 0.095;  // the mesh's radius; the analytic drum of the comparison: this
  const TriangleMesh mesh = tube(inner, 0.05, 96);
  ASSERT_EQ(mesh.patches, 1u);
  write_stl(mesh, dir.path() / "tube.stl");
  test::SmallDrumText plain;
  plain.diameter = "0.19";
  plain.fill = "count = 300\nsettle_time = 0.3";
  test::SmallDrumText meshed = plain;
  meshed.diameter = "0.2";
  meshed.wall = "friction = 0.5\n[[wall.mesh]]\nfile = \"tube.stl\"";
  const SceneConfig a = parse_scene(plain.text(), (dir.path() / "plain.toml").string());
  const SceneConfig b = parse_scene(meshed.text(), (dir.path() / "meshed.toml").string());
  const Particles start = random_fill(a);  // inside the smaller drum: inside the tube
  Simulation analytic(a, start), faceted(b, start);
  analytic.set_drum_omega(0.0);
  faceted.set_drum_omega(0.0);
  analytic.advance(3000);  // settle
  faceted.advance(3000);
  analytic.set_drum_omega(2.0);
  faceted.set_drum_omega(2.0);
  analytic.advance(15000);  // the bed's first slump, into the steady avalanches
  faceted.advance(15000);
  const std::vector<double> x = angles(analytic, 60), y = angles(faceted, 60);
  const auto mean = [](const std::vector<double>& v) {
    double s = 0.0;
    for (const double a : v) s += a;
    return s / static_cast<double>(v.size());
  };
  const auto sd = [&](const std::vector<double>& v) {
    const double m = mean(v);
    double s = 0.0;
    for (const double a : v) s += (a - m) * (a - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
  };
  // The window's noise: the samples' spread over the window (the avalanches).
  const double noise = std::max(sd(x), sd(y));
  std::printf(
      "angle of repose (centre of mass): analytic D = 0.19 m %.2f +- %.2f deg, 96 "
      "facets of radius 0.095 m %.2f +- %.2f deg (difference %.2f deg)\n",
      mean(x), sd(x), mean(y), sd(y), mean(y) - mean(x));
  EXPECT_GT(mean(x), 10.0);  // the bed was lifted
  EXPECT_LT(std::abs(mean(y) - mean(x)), noise);
  // The bed never reached the analytic mantle behind the facets.
  for (std::size_t i = 0; i < faceted.particles().size(); ++i) {
    const Vec3& p = faceted.particles().position[i];
    EXPECT_LT(std::hypot(p.x(), p.y()), inner) << i;
  }
}

}  // namespace
}  // namespace drumlab
