// Random fill: exact class counts, no overlaps, inside the drum, in its lower part, reproducible.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "engine/fill/random_fill.hpp"
#include "overlap_check.hpp"

namespace drumlab {
namespace {

SceneConfig scene_file(const char* name) {
  return load_scene(std::filesystem::path(DRUMLAB_SCENES_DIR) / name);
}

std::vector<std::size_t> counts_by_class(const Particles& p, std::size_t classes) {
  std::vector<std::size_t> n(classes, 0);
  for (auto c : p.size_class) ++n.at(c);
  return n;
}

/// Largest amount by which a sphere sticks out of the drum (mantle or end planes); <= 0 if none.
double max_protrusion(const Particles& p, const SceneConfig& s) {
  const double R = 0.5 * s.drum.diameter;
  double worst = -1e300;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    const double r = p.radius[i];
    worst =
        std::max({worst, std::hypot(x.x(), x.y()) + r - R, r - x.z(), x.z() + r - s.drum.depth});
  }
  return worst;
}

TEST(RandomFill, ClassCountsSplitByVolumeExactly) {
  const SceneConfig demo = scene_file("drum_demo.toml");
  EXPECT_EQ(class_counts(demo), (std::vector<std::size_t>{16200, 2025, 600}));
  const SceneConfig paper = scene_file("drum_paper.toml");
  EXPECT_EQ(class_counts(paper), (std::vector<std::size_t>{64800, 8100, 2400}));
  const SceneConfig teach = scene_file("teach_stencil.toml");
  EXPECT_EQ(class_counts(teach), (std::vector<std::size_t>{432, 54, 16}));
}

TEST(RandomFill, ClassCountsAlwaysSumToTheCount) {
  SceneConfig s = scene_file("drum_demo.toml");
  s.classes[0].volume_fraction = 0.3;
  s.classes[1].volume_fraction = 0.3;
  s.classes[2].volume_fraction = 0.4;
  for (std::size_t n : {1u, 2u, 3u, 7u, 1001u, 18826u, 99999u}) {
    s.fill.count = n;
    const auto c = class_counts(s);
    EXPECT_EQ(c[0] + c[1] + c[2], n) << "count " << n;
    // Each class within one particle of its exact share.
    const double w0 = 0.3 / 1.0, w1 = 0.3 / 8.0, w2 = 0.4 / 27.0;  // radius ratio 1 : 2 : 3
    const double exact0 = static_cast<double>(n) * w0 / (w0 + w1 + w2);
    EXPECT_LT(std::abs(static_cast<double>(c[0]) - exact0), 1.0) << "count " << n;
  }
}

TEST(RandomFill, DemoSceneHasNoOverlapsAndStaysInTheLowerDrum) {
  const SceneConfig s = scene_file("drum_demo.toml");
  const Particles p = random_fill(s);
  ASSERT_EQ(p.size(), 18825u);
  EXPECT_EQ(counts_by_class(p, 3), (std::vector<std::size_t>{16200, 2025, 600}));
  EXPECT_LE(max_protrusion(p, s), 1e-12);
  EXPECT_LE(test::max_overlap_grid(p), 0.0);
  double mean_y = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.radius[i], s.classes[p.size_class[i]].radius);
    EXPECT_EQ(p.id[i], i);
    EXPECT_EQ(p.velocity[i], Vec3::Zero());
    EXPECT_NEAR(p.mass[i], 2500.0 * 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius[i], 3), 1e-15);
    mean_y += p.position[i].y() / static_cast<double>(p.size());
  }
  EXPECT_LT(mean_y, -0.1 * s.drum.diameter);
}

TEST(RandomFill, BruteForceFindsNoOverlap) {
  for (const char* name : {"tilted_drum.toml", "mono_periodic.toml", "teach_stencil.toml"}) {
    SCOPED_TRACE(name);
    const SceneConfig s = scene_file(name);
    const Particles p = random_fill(s);
    ASSERT_EQ(p.size(), s.fill.count);
    EXPECT_LE(test::max_overlap_brute_force(p), 0.0);
    EXPECT_LE(max_protrusion(p, s), 1e-12);
  }
}

TEST(RandomFill, SameSeedSameParticlesOtherSeedOtherParticles) {
  SceneConfig s = scene_file("teach_stencil.toml");
  const Particles a = random_fill(s);
  const Particles b = random_fill(s);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.size_class, b.size_class);
  s.fill.seed += 1;
  const Particles c = random_fill(s);
  EXPECT_NE(a.position, c.position);
}

TEST(RandomFill, LooserFillReachesHigher) {
  SceneConfig s = scene_file("teach_stencil.toml");
  auto top = [](const Particles& p) {
    double y = -1e300;
    for (const auto& x : p.position) y = std::max(y, x.y());
    return y;
  };
  s.fill.volume_fraction = 0.35;
  const double dense = top(random_fill(s));
  s.fill.volume_fraction = 0.15;
  const double loose = top(random_fill(s));
  EXPECT_GT(loose, dense + 0.02);
}

TEST(RandomFill, FollowsTheInPlaneGravity) {
  SceneConfig s = scene_file("teach_stencil.toml");
  s.gravity = Vec3(9.81, 0.0, 0.0);  // "down" is +x
  const Particles p = random_fill(s);
  double mean_x = 0.0;
  for (const auto& x : p.position) mean_x += x.x() / static_cast<double>(p.size());
  EXPECT_GT(mean_x, 0.1 * s.drum.diameter);
  EXPECT_LE(test::max_overlap_brute_force(p), 0.0);
}

TEST(RandomFill, ImpossibleFillIsAnInputError) {
  SceneConfig s = scene_file("teach_stencil.toml");
  s.fill.count = 20000;  // about twice the drum's volume in spheres
  try {
    random_fill(s);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(s.source + ": fill: cannot place"), std::string::npos) << message;
    EXPECT_NE(message.find("lower fill.count or fill.volume_fraction"), std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace drumlab
