// `auto` picks a method that exists, says why, and states the paper's rule as the baseline.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "engine/fill/random_fill.hpp"
#include "engine/search/auto_select.hpp"
#include "engine/search/contact_search.hpp"

namespace drumlab {
namespace {

TEST(AutoSelect, ShallowAndDeepDrums) {
  for (const char* file : {"teach_stencil.toml", "tilted_drum.toml"}) {
    const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/" + file);
    const Particles p = random_fill(scene);
    const SearchChoice choice = choose_search_method(scene, 1e-4, p.position, p.radius, 2);
    EXPECT_NO_THROW(make_search(choice.method)) << choice.method;
    EXPECT_EQ(choice.paper_rule, scene.drum.depth / scene.drum.diameter < 0.5 ? "m2" : "m5");
    EXPECT_NE(choice.reason.find("paper's rule picks " + choice.paper_rule), std::string::npos);
    ASSERT_EQ(choice.candidates.size(), 6u);
    // The ranking is by the model; the first two were timed.
    EXPECT_LE(choice.candidates[0].model_ns_per_particle,
              choice.candidates[1].model_ns_per_particle);
    EXPECT_GT(choice.candidates[1].measured_ns_per_particle, 0.0);
    EXPECT_LT(choice.candidates[2].measured_ns_per_particle, 0.0);
  }
}

TEST(AutoSelect, VerletListOnlyWhenRebuildsAreRare) {
  const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml");
  const Particles p = random_fill(scene);
  EXPECT_TRUE(
      choose_search_method(scene, 1e-5, p.position, p.radius, 0).method.starts_with("verlet:"));
  EXPECT_FALSE(
      choose_search_method(scene, 1e-2, p.position, p.radius, 0).method.starts_with("verlet"));
  // The expected rebuild interval uses the scene's skin: a wider skin keeps the list longer.
  SceneConfig wide = scene;
  wide.performance.verlet_skin = 4.0 * scene.performance.verlet_skin;
  const SearchChoice narrow_choice = choose_search_method(scene, 1e-4, p.position, p.radius, 0);
  const SearchChoice wide_choice = choose_search_method(wide, 1e-4, p.position, p.radius, 0);
  const auto skin_text = [](double f) { return fmt::format("skin {} R_min", f); };
  EXPECT_NE(narrow_choice.reason.find(skin_text(scene.performance.verlet_skin)), std::string::npos)
      << narrow_choice.reason;
  EXPECT_NE(wide_choice.reason.find(skin_text(wide.performance.verlet_skin)), std::string::npos)
      << wide_choice.reason;
}

TEST(AutoSelect, GridsAreRankedOnTheVerletListTheyWouldBuild) {
  // With a Verlet list, the grid's work is building the list: it is counted with the skin as the
  // margin, so each grid tests more pairs than as a plain contact search.
  const SceneConfig scene = load_scene(std::string(DRUMLAB_SCENES_DIR) + "/teach_stencil.toml");
  const Particles p = random_fill(scene);
  const SearchChoice list = choose_search_method(scene, 1e-5, p.position, p.radius, 0);
  const SearchChoice plain = choose_search_method(scene, 1e-2, p.position, p.radius, 0);
  ASSERT_TRUE(list.method.starts_with("verlet:"));
  ASSERT_FALSE(plain.method.starts_with("verlet"));
  const auto tests_of = [](const SearchChoice& c, const std::string& method) {
    for (const MethodEstimate& e : c.candidates) {
      if (e.method == method) return e.tests_per_particle;
    }
    return -1.0;
  };
  for (const char* method : {"m2", "m5", "mlgrid"}) {
    EXPECT_GT(tests_of(list, method), tests_of(plain, method)) << method;
  }
  EXPECT_NE(list.reason.find("Verlet skin as margin"), std::string::npos) << list.reason;
  EXPECT_EQ(plain.reason.find("Verlet skin as margin"), std::string::npos) << plain.reason;
}

}  // namespace
}  // namespace drumlab
