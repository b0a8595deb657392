// The material ranges (engine/scene/material_check.hpp) are the loader's and the contact model's:
// the first failing key and its reason, and the contact model refusing a material built in code.
#include <gtest/gtest.h>

#include "engine/contact/contact_model.hpp"
#include "engine/scene/material_check.hpp"

namespace drumlab {
namespace {

TEST(MaterialCheck, FirstFailingKeyAndReason) {
  EXPECT_FALSE(material_problem(Material{}).has_value());
  Material m;
  m.poisson_ratio = 0.5;
  m.friction = -1.0;
  const auto p = material_problem(m);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->key, "poisson_ratio");
  EXPECT_EQ(p->reason, "must be in (-1, 0.5), got 0.5");
  EXPECT_EQ(material_value_problem("friction", -1.0), "must be >= 0, got -1");
  EXPECT_EQ(material_value_problem("restitution", 0.0), "must be in (0, 1], got 0");
  EXPECT_EQ(material_value_problem("density", 0.0), "must be > 0, got 0");
  EXPECT_FALSE(material_value_problem("rolling_friction", 0.0).has_value());
}

TEST(MaterialCheck, ContactModelNamesTheTableAndKey) {
  SceneConfig s;
  s.wall.youngs_modulus = -5.0;
  try {
    ContactModel model(s);
    FAIL() << "accepted a negative Young's modulus";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "scene: wall.youngs_modulus: must be > 0, got -5");
  }
}

}  // namespace
}  // namespace drumlab
