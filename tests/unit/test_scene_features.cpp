// scene_features() against what the engine actually composes: the contact model's flags for every
// friction / rolling combination, the drum's ends, and a run in which skipped rotation leaves the
// angular velocities exactly zero. Plus the shallow-drum rule and the lines `drumlab info` prints.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "engine/contact/contact_model.hpp"
#include "engine/drum.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/scene/scene_features.hpp"
#include "engine/simulation.hpp"
#include "tests/small_drum_text.hpp"

namespace drumlab {
namespace {

struct Knobs {
  double friction = 0.5;
  double wall_friction = 0.5;
  double rolling = 0.0;
  double wall_rolling = 0.0;
  const char* ends = "caps";
  double depth = 0.05;
  const char* search = "m5";
};

SceneConfig scene_with(const Knobs& k) {
  test::SmallDrumText t;
  t.search = k.search;
  t.depth = fmt::format("{}", k.depth);
  t.ends = k.ends;
  t.friction = fmt::format("{}", k.friction);
  t.rolling_friction = fmt::format("{}", k.rolling);
  t.wall = fmt::format("friction = {}\nrolling_friction = {}", k.wall_friction, k.wall_rolling);
  return parse_scene(t.text(), "features.toml");
}

const SceneFeature& line(const SceneFeatures& f, const std::string& prefix) {
  const auto it = std::find_if(f.list.begin(), f.list.end(),
                               [&](const SceneFeature& x) { return x.term.rfind(prefix, 0) == 0; });
  EXPECT_NE(it, f.list.end()) << prefix;
  return *it;
}

TEST(SceneFeatures, ContactTermsAgreeWithTheComposedContactModel) {
  for (int mask = 0; mask < 16; ++mask) {
    Knobs k;
    k.friction = (mask & 1) ? 0.5 : 0.0;
    k.wall_friction = (mask & 2) ? 0.3 : 0.0;
    k.rolling = (mask & 4) ? 0.01 : 0.0;
    k.wall_rolling = (mask & 8) ? 0.02 : 0.0;
    const SceneConfig scene = scene_with(k);
    const SceneFeatures f = scene_features(scene);
    const ContactModel model(scene);
    SCOPED_TRACE(mask);
    EXPECT_EQ(f.pair_tangential, model.pair_tangential());
    EXPECT_EQ(f.wall_tangential, model.wall_tangential());
    EXPECT_EQ(f.pair_rolling, model.pair_rolling());
    EXPECT_EQ(f.wall_rolling, model.wall_rolling());
    EXPECT_EQ(f.rotation, model.uses_rotation());
    EXPECT_EQ(f.rotation, mask != 0);
    EXPECT_FALSE(f.cohesion);
    EXPECT_EQ(line(f, "cohesion").use, FeatureUse::skipped);
    EXPECT_EQ(line(f, "tangential history (particle-particle)").use,
              f.pair_tangential ? FeatureUse::needed : FeatureUse::skipped);
    EXPECT_EQ(line(f, "rotation").use, f.rotation ? FeatureUse::needed : FeatureUse::skipped);
  }
}

TEST(SceneFeatures, EndCapsFollowTheDrumEnds) {
  Knobs k;
  const SceneConfig caps = scene_with(k);
  k.ends = "periodic";
  const SceneConfig periodic = scene_with(k);
  EXPECT_TRUE(scene_features(caps).end_caps);
  EXPECT_FALSE(Drum(caps.drum).periodic());
  EXPECT_FALSE(scene_features(periodic).end_caps);
  EXPECT_TRUE(Drum(periodic.drum).periodic());
  EXPECT_EQ(line(scene_features(periodic), "end-cap contacts").use, FeatureUse::skipped);
}

TEST(SceneFeatures, ShallowDrumNeedsNo3DGrid) {
  Knobs k;  // depth 0.05 m, largest diameter 0.016 m: 3.1 diameters
  const SceneFeatures m5 = scene_features(scene_with(k));
  EXPECT_TRUE(m5.shallow);
  EXPECT_NEAR(m5.depth_in_diameters, 0.05 / 0.016, 1e-12);
  EXPECT_FALSE(m5.grid_2d);
  EXPECT_EQ(line(m5, "3D search grid").use, FeatureUse::available);
  k.search = "verlet:m2";
  const SceneFeatures m2 = scene_features(scene_with(k));
  EXPECT_TRUE(m2.grid_2d);
  EXPECT_EQ(line(m2, "3D search grid").use, FeatureUse::skipped);
  k.depth = 0.2;  // 12.5 diameters
  const SceneFeatures deep = scene_features(scene_with(k));
  EXPECT_FALSE(deep.shallow);
  EXPECT_EQ(line(deep, "3D search grid").use, FeatureUse::needed);
  EXPECT_EQ(line(deep, "output writers").use, FeatureUse::command_line);
}

/// Largest |omega| over all particles after `steps` steps of the turning drum.
double max_spin_after(const SceneConfig& scene, int steps) {
  Simulation sim(scene, random_fill(scene));
  sim.advance(static_cast<std::uint64_t>(steps));
  double w = 0.0;
  for (const Vec3& o : sim.particles().omega) w = std::max(w, o.norm());
  return w;
}

TEST(SceneFeatures, SkippedRotationLeavesAngularVelocitiesExactlyZero) {
  Knobs k;
  k.friction = 0.0;
  k.wall_friction = 0.0;
  const SceneConfig frictionless = scene_with(k);
  ASSERT_FALSE(scene_features(frictionless).rotation);
  EXPECT_EQ(max_spin_after(frictionless, 300), 0.0);
  k.wall_friction = 0.5;  // the turning wall now spins the particles it touches
  const SceneConfig wall_friction = scene_with(k);
  ASSERT_TRUE(scene_features(wall_friction).rotation);
  EXPECT_GT(max_spin_after(wall_friction, 300), 0.0);
}

}  // namespace
}  // namespace drumlab
