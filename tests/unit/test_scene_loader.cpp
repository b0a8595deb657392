// Scene files: every shipped scene loads; values round-trip; every bad input is one clear line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <string>

#include "engine/scene/scene_config.hpp"

namespace drumlab {
namespace {

const char* const kGoodScene = R"(name = "roundtrip"
description = "every key set"
gravity = [0.5, -9.0, 0.25]
search = "m3"

[drum]
diameter = 0.9
depth = 0.15
omega = 2.5
tilt_deg = 30.0
ends = "periodic"

[[particles]]
name = "small"
radius = 0.005
volume_fraction = 0.25

[[particles]]
name = "large"
radius = 0.015
volume_fraction = 0.75

[material]
density = 2600.0
youngs_modulus = 1e7
poisson_ratio = 0.25
restitution = 0.6
friction = 0.4
rolling_friction = 0.01

[wall]
friction = 0.0
restitution = 0.8

[contact]
normal = "linear"
linear_stiffness = 1e5

[fill]
kind = "random"
count = 1000
volume_fraction = 0.3
seed = 42
settle_time = 0.25

[time]
dt = 1e-5
revolutions = 0.5

[output]
directory = "out/x"
diagnostics_every = 50
)";

/// kGoodScene with the first occurrence of `from` replaced by `to` (the test fails if absent).
std::string edited(const std::string& from, const std::string& to) {
  std::string text = kGoodScene;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the scene";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// The InputError message for `text` parsed as "bad.toml", or "" if it parsed.
std::string error_for(const std::string& text) {
  try {
    parse_scene(text, "bad.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneLoader, EveryShippedSceneLoads) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(DRUMLAB_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    SceneConfig scene;
    ASSERT_NO_THROW(scene = load_scene(entry.path()));
    EXPECT_EQ(scene.name, entry.path().stem().string());
    EXPECT_EQ(scene.source, entry.path().string());
    EXPECT_FALSE(scene.description.empty());
    EXPECT_FALSE(scene.classes.empty());
    names.insert(scene.name);
  }
  for (const char* expected : {"drum_demo", "drum_paper", "paper_table1", "paper_table2",
                               "teach_stencil", "tilted_drum", "mono_periodic"}) {
    EXPECT_TRUE(names.count(expected)) << expected << ".toml missing from scenes/";
  }
}

TEST(SceneLoader, DemoSceneHasThePaperProportions) {
  const SceneConfig s = load_scene(std::filesystem::path(DRUMLAB_SCENES_DIR) / "drum_demo.toml");
  EXPECT_DOUBLE_EQ(s.drum.diameter, 60.0 * s.max_radius());
  EXPECT_DOUBLE_EQ(s.drum.depth, 10.0 * s.max_radius());
  EXPECT_DOUBLE_EQ(s.max_radius(), 3.0 * s.min_radius());
  EXPECT_EQ(s.fill.count, 18825u);
  EXPECT_EQ(s.drum.ends, DrumEnds::caps);
  const double froude = s.drum.omega * s.drum.omega * 0.5 * s.drum.diameter / 9.81;
  EXPECT_NEAR(froude, 0.046, 0.001);
  const SceneConfig t = load_scene(std::filesystem::path(DRUMLAB_SCENES_DIR) / "tilted_drum.toml");
  EXPECT_DOUBLE_EQ(t.drum.depth, t.drum.diameter);
  EXPECT_NEAR(t.drum.tilt, 20.0 * std::numbers::pi / 180.0, 1e-12);
}

TEST(SceneLoader, GoodValuesRoundTrip) {
  const SceneConfig s = parse_scene(kGoodScene, "good.toml");
  EXPECT_EQ(s.name, "roundtrip");
  EXPECT_EQ(s.source, "good.toml");
  EXPECT_EQ(s.description, "every key set");
  EXPECT_EQ(s.gravity, Vec3(0.5, -9.0, 0.25));
  EXPECT_EQ(s.search_method, "m3");
  EXPECT_DOUBLE_EQ(s.drum.diameter, 0.9);
  EXPECT_DOUBLE_EQ(s.drum.depth, 0.15);
  EXPECT_DOUBLE_EQ(s.drum.omega, 2.5);
  EXPECT_NEAR(s.drum.tilt, std::numbers::pi / 6.0, 1e-15);
  EXPECT_EQ(s.drum.ends, DrumEnds::periodic);
  ASSERT_EQ(s.classes.size(), 2u);
  EXPECT_EQ(s.classes[0].name, "small");
  EXPECT_DOUBLE_EQ(s.classes[0].radius, 0.005);
  EXPECT_DOUBLE_EQ(s.classes[0].volume_fraction, 0.25);
  EXPECT_EQ(s.classes[1].name, "large");
  EXPECT_DOUBLE_EQ(s.classes[1].radius, 0.015);
  EXPECT_DOUBLE_EQ(s.min_radius(), 0.005);
  EXPECT_DOUBLE_EQ(s.max_radius(), 0.015);
  EXPECT_DOUBLE_EQ(s.material.density, 2600.0);
  EXPECT_DOUBLE_EQ(s.material.youngs_modulus, 1e7);
  EXPECT_DOUBLE_EQ(s.material.poisson_ratio, 0.25);
  EXPECT_DOUBLE_EQ(s.material.restitution, 0.6);
  EXPECT_DOUBLE_EQ(s.material.friction, 0.4);
  EXPECT_DOUBLE_EQ(s.material.rolling_friction, 0.01);
  // [wall] overrides two keys; the rest come from [material].
  EXPECT_DOUBLE_EQ(s.wall.friction, 0.0);
  EXPECT_DOUBLE_EQ(s.wall.restitution, 0.8);
  EXPECT_DOUBLE_EQ(s.wall.youngs_modulus, 1e7);
  EXPECT_DOUBLE_EQ(s.wall.poisson_ratio, 0.25);
  EXPECT_DOUBLE_EQ(s.wall.rolling_friction, 0.01);
  EXPECT_EQ(s.contact.normal, NormalLaw::linear);
  EXPECT_DOUBLE_EQ(s.contact.linear_stiffness, 1e5);
  EXPECT_EQ(s.fill.kind, FillKind::random);
  EXPECT_EQ(s.fill.count, 1000u);
  EXPECT_DOUBLE_EQ(s.fill.volume_fraction, 0.3);
  EXPECT_EQ(s.fill.seed, 42u);
  EXPECT_DOUBLE_EQ(s.fill.settle_time, 0.25);
  ASSERT_TRUE(s.time.dt.has_value());
  EXPECT_DOUBLE_EQ(*s.time.dt, 1e-5);
  EXPECT_FALSE(s.time.duration.has_value());
  ASSERT_TRUE(s.time.revolutions.has_value());
  EXPECT_DOUBLE_EQ(*s.time.revolutions, 0.5);
  EXPECT_EQ(s.output.directory, "out/x");
  EXPECT_EQ(s.output.diagnostics_every, 50u);
}

TEST(SceneLoader, DefaultsAndAlternatives) {
  std::string text = kGoodScene;
  text.erase(0, text.find('\n') + 1);  // no name: taken from the file name
  text.erase(text.find("[wall]"), text.find("[contact]") - text.find("[wall]"));
  text.erase(text.find("[output]"));
  const auto at = text.find("omega = 2.5");
  text.replace(at, 11, "rpm = 30");
  const SceneConfig s = parse_scene(text, "dir/my_drum.toml");
  EXPECT_EQ(s.name, "my_drum");
  EXPECT_NEAR(s.drum.omega, std::numbers::pi, 1e-12);
  EXPECT_EQ(s.output.directory, "out/my_drum");
  EXPECT_EQ(s.output.diagnostics_every, 1000u);
  EXPECT_DOUBLE_EQ(s.wall.friction, s.material.friction);  // wall defaults to the material
  EXPECT_DOUBLE_EQ(s.wall.restitution, s.material.restitution);
}

TEST(SceneLoader, PaperPackingScene) {
  const SceneConfig s = load_scene(std::filesystem::path(DRUMLAB_SCENES_DIR) / "paper_table2.toml");
  EXPECT_EQ(s.fill.kind, FillKind::paper_packing);
  EXPECT_EQ(s.fill.box, Vec3(1.85, 1.80, 2.0));
  EXPECT_DOUBLE_EQ(s.drum.depth, 2.0);
  EXPECT_DOUBLE_EQ(s.drum.diameter, 1.8);
}

struct BadCase {
  const char* what;
  std::string text;
  const char* key;  ///< must appear in the message, right after "bad.toml: "
};

TEST(SceneLoader, BadInputGivesOneLineNamingFileAndKey) {
  const std::vector<BadCase> cases = {
      {"unknown top-level key", "colour = 1\n" + std::string(kGoodScene), "colour"},
      {"unknown drum key", edited("depth = 0.15", "depth = 0.15\ndepht = 0.2"), "drum.depht"},
      {"unknown class key", edited("volume_fraction = 0.75", "volume_fraction = 0.75\nr = 1"),
       "particles[1].r"},
      {"unknown fill key", edited("seed = 42", "seed = 42\nsede = 1"), "fill.sede"},
      {"wrong type", edited("diameter = 0.9", "diameter = \"big\""), "drum.diameter"},
      {"wrong type for integer", edited("count = 1000", "count = 1000.5"), "fill.count"},
      {"table expected", "wall = 1\n" + edited("[wall]\nfriction = 0.0\nrestitution = 0.8", ""),
       "wall"},
      {"negative radius", edited("radius = 0.005", "radius = -0.005"), "particles[0].radius"},
      {"zero radius", edited("radius = 0.015", "radius = 0"), "particles[1].radius"},
      {"missing radius", edited("radius = 0.015", ""), "particles[1].radius"},
      {"restitution 1.5", edited("restitution = 0.6", "restitution = 1.5"), "material.restitution"},
      {"wall restitution 0", edited("restitution = 0.8", "restitution = 0.0"), "wall.restitution"},
      {"poisson 0.5", edited("poisson_ratio = 0.25", "poisson_ratio = 0.5"),
       "material.poisson_ratio"},
      {"density 0", edited("density = 2600.0", "density = 0.0"), "material.density"},
      {"missing friction", edited("friction = 0.4", ""), "material.friction"},
      {"density in wall", edited("[wall]", "[wall]\ndensity = 1.0"), "wall.density"},
      {"fractions sum", edited("volume_fraction = 0.25", "volume_fraction = 0.2"), "particles"},
      {"drum too small", edited("diameter = 0.9", "diameter = 0.03"), "drum.diameter"},
      {"tilt 90", edited("tilt_deg = 30.0", "tilt_deg = 90.0"), "drum.tilt_deg"},
      {"unknown ends", edited("\"periodic\"", "\"open\""), "drum.ends"},
      {"omega and rpm", edited("omega = 2.5", "omega = 2.5\nrpm = 10"), "drum.rpm"},
      {"no omega", edited("omega = 2.5", ""), "drum.omega"},
      {"unknown fill kind", edited("kind = \"random\"", "kind = \"pour\""), "fill.kind"},
      {"count 0", edited("count = 1000", "count = 0"), "fill.count"},
      {"box in a random fill", edited("seed = 42", "seed = 42\nbox = [1, 1, 1]"), "fill.box"},
      {"unknown normal law", edited("\"linear\"", "\"jkr\""), "contact.normal"},
      {"linear without stiffness", edited("linear_stiffness = 1e5", ""),
       "contact.linear_stiffness"},
      {"collision time with the linear law",
       edited("linear_stiffness = 1e5", "linear_stiffness = 1e5\ncollision_time = 1e-3"),
       "contact.collision_time"},
      {"linear_viscoelastic without collision time",
       edited("normal = \"linear\"\nlinear_stiffness = 1e5",
              "normal = \"linear_viscoelastic\"\nreference_radius = 0.01"),
       "contact.collision_time"},
      {"linear_viscoelastic without reference radius",
       edited("normal = \"linear\"\nlinear_stiffness = 1e5",
              "normal = \"linear_viscoelastic\"\ncollision_time = 1e-3"),
       "contact.reference_radius"},
      {"linear_viscoelastic with a stiffness",
       edited("normal = \"linear\"",
              "normal = \"linear_viscoelastic\"\ncollision_time = 1e-3\nreference_radius = 0.01"),
       "contact.linear_stiffness"},
      {"collision time 0",
       edited("normal = \"linear\"\nlinear_stiffness = 1e5",
              "normal = \"linear_viscoelastic\"\ncollision_time = 0\nreference_radius = 0.01"),
       "contact.collision_time"},
      {"tangential stiffness ratio 0",
       edited("normal = \"linear\"\nlinear_stiffness = 1e5",
              "normal = \"linear_viscoelastic\"\ncollision_time = 1e-3\nreference_radius = "
              "0.01\ntangential_stiffness_ratio = 0"),
       "contact.tangential_stiffness_ratio"},
      {"tangential damping ratio -1",
       edited("normal = \"linear\"\nlinear_stiffness = 1e5",
              "normal = \"linear_viscoelastic\"\ncollision_time = 1e-3\nreference_radius = "
              "0.01\ntangential_damping_ratio = -1"),
       "contact.tangential_damping_ratio"},
      {"rolling spring with the linear law",
       edited("linear_stiffness = 1e5", "linear_stiffness = 1e5\nrolling = \"spring\""),
       "contact.rolling"},
      {"unknown rolling law",
       edited("linear_stiffness = 1e5", "linear_stiffness = 1e5\nrolling = \"cdt\""),
       "contact.rolling"},
      {"rolling ratio without the spring",
       edited("linear_stiffness = 1e5", "linear_stiffness = 1e5\nrolling_damping_ratio = 0.1"),
       "contact.rolling_damping_ratio"},
      {"rolling stiffness ratio 0",
       edited("normal = \"linear\"\nlinear_stiffness = 1e5",
              "normal = \"linear_viscoelastic\"\ncollision_time = 1e-3\nreference_radius = "
              "0.01\nrolling = \"spring\"\nrolling_stiffness_ratio = 0"),
       "contact.rolling_stiffness_ratio"},
      {"dt and dt_factor", edited("dt = 1e-5", "dt = 1e-5\ndt_factor = 0.1"), "time.dt_factor"},
      {"duration and revolutions", edited("revolutions = 0.5", "revolutions = 0.5\nduration = 1"),
       "time.revolutions"},
      {"no run length", edited("revolutions = 0.5", ""), "time.duration"},
      {"max_overlap 0", edited("revolutions = 0.5", "revolutions = 0.5\nmax_overlap = 0"),
       "time.max_overlap"},
      {"gravity of two numbers", edited("[0.5, -9.0, 0.25]", "[0.5, -9.0]"), "gravity"},
      {"missing material", edited("[material]", "[materials]"), "materials"},
      {"diagnostics_every 0", edited("diagnostics_every = 50", "diagnostics_every = 0"),
       "output.diagnostics_every"},
      {"not finite", edited("depth = 0.15", "depth = inf"), "drum.depth"},
      {"negative sort interval", edited("[output]", "[performance]\nsort_every = -1\n[output]"),
       "performance.sort_every"},
      {"zero skin", edited("[output]", "[performance]\nverlet_skin = 0\n[output]"),
       "performance.verlet_skin"},
      {"tiny row blocks", edited("[output]", "[performance]\npair_block_rows = 63\n[output]"),
       "performance.pair_block_rows"},
      {"negative row blocks",
       edited("[output]", "[performance]\npair_block_rows = -2048\n[output]"),
       "performance.pair_block_rows"},
      {"unknown performance key", edited("[output]", "[performance]\nsort = 5\n[output]"),
       "performance.sort"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string message = error_for(c.text);
    ASSERT_FALSE(message.empty()) << "no InputError";
    EXPECT_EQ(message.rfind("bad.toml: ", 0), 0u) << message;
    EXPECT_NE(message.find(std::string("bad.toml: ") + c.key + ":"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(SceneLoader, PerformanceKnobs) {
  const SceneConfig defaults = parse_scene(kGoodScene, "good.toml");
  EXPECT_EQ(defaults.performance.sort_every, 100u);
  EXPECT_DOUBLE_EQ(defaults.performance.verlet_skin, 1.0);
  EXPECT_EQ(defaults.performance.pair_block_rows, 512u);
  const SceneConfig s = parse_scene(
      edited("[output]",
             "[performance]\nsort_every = 0\nverlet_skin = 0.8\npair_block_rows = 64\n[output]"),
      "p.toml");
  EXPECT_EQ(s.performance.sort_every, 0u);
  EXPECT_DOUBLE_EQ(s.performance.verlet_skin, 0.8);
  EXPECT_EQ(s.performance.pair_block_rows, 64u);
}

TEST(SceneLoader, LiquidBridgeKeys) {
  const SceneConfig dry = parse_scene(kGoodScene, "good.toml");
  EXPECT_FALSE(dry.liquid.enabled);
  const std::string liquid =
      "[liquid]\nsurface_tension = 0.072\ncontact_angle_deg = 20\nbridge_volume = 1e-12\n[output]";
  const SceneConfig wet = parse_scene(edited("[output]", liquid), "wet.toml");
  EXPECT_TRUE(wet.liquid.enabled);
  EXPECT_DOUBLE_EQ(wet.liquid.surface_tension, 0.072);
  EXPECT_DOUBLE_EQ(wet.liquid.contact_angle_deg, 20.0);
  EXPECT_DOUBLE_EQ(wet.liquid.bridge_volume, 1e-12);
  const SceneConfig default_angle = parse_scene(
      edited("[output]", "[liquid]\nsurface_tension = 0.07\nbridge_volume = 1e-12\n[output]"),
      "wet.toml");
  EXPECT_DOUBLE_EQ(default_angle.liquid.contact_angle_deg, 0.0);
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = liquid;
    text.replace(text.find(from), from.size(), to);
    return edited("[output]", text);
  };
  const std::vector<BadCase> cases = {
      {"negative surface tension", with("0.072", "-0.01"), "liquid.surface_tension"},
      {"missing surface tension", with("surface_tension = 0.072\n", ""), "liquid.surface_tension"},
      {"angle 90", with("= 20", "= 90"), "liquid.contact_angle_deg"},
      {"negative angle", with("= 20", "= -1"), "liquid.contact_angle_deg"},
      {"zero volume", with("1e-12", "0"), "liquid.bridge_volume"},
      {"missing volume", with("bridge_volume = 1e-12\n", ""), "liquid.bridge_volume"},
      {"unknown liquid key", with("[liquid]", "[liquid]\nvolume = 1"), "liquid.volume"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string message = error_for(c.text);
    ASSERT_FALSE(message.empty()) << "no InputError";
    EXPECT_NE(message.find(std::string("bad.toml: ") + c.key + ":"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(SceneLoader, MissingRequiredTable) {
  std::string text = kGoodScene;
  text.erase(text.find("[fill]"), text.find("[time]") - text.find("[fill]"));
  const std::string message = error_for(text);
  EXPECT_NE(message.find("bad.toml: fill: missing"), std::string::npos) << message;
}

TEST(SceneLoader, PaperPackingNeedsThreeClassesAndABox) {
  std::string text = edited(
      "kind = \"random\"\ncount = 1000\nvolume_fraction = 0.3\nseed = 42\n"
      "settle_time = 0.25",
      "kind = \"paper_packing\"");
  std::string message = error_for(text);
  EXPECT_NE(message.find("bad.toml: fill.box: missing"), std::string::npos) << message;
  const auto at = text.find("kind = \"paper_packing\"");
  text.insert(at + 22, "\nbox = [1.0, 1.0, 0.1]");
  message = error_for(text);  // two classes only
  EXPECT_NE(message.find("bad.toml: fill.kind:"), std::string::npos) << message;
  EXPECT_NE(message.find("three"), std::string::npos) << message;
}

TEST(SceneLoader, SyntaxErrorNamesLineAndColumn) {
  const std::string message = error_for(edited("diameter = 0.9", "diameter = = 0.9"));
  EXPECT_EQ(message.rfind("bad.toml: line 7, column", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  const std::string duplicate = error_for(edited("depth = 0.15", "depth = 0.15\ndepth = 0.2"));
  EXPECT_EQ(duplicate.rfind("bad.toml: line 9", 0), 0u) << duplicate;
}

TEST(SceneLoader, MissingFile) {
  const std::filesystem::path missing =
      std::filesystem::temp_directory_path() / "drumlab_no_such_scene.toml";
  try {
    load_scene(missing);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), missing.string() + ": cannot read scene file");
  }
  EXPECT_THROW(load_scene(std::filesystem::temp_directory_path()), InputError);
}

TEST(SceneLoader, LoadsFromDiskWithThePathInErrors) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "drumlab_test_bad_scene.toml";
  {
    std::ofstream out(file);
    out << edited("restitution = 0.6", "restitution = 1.5");
  }
  try {
    load_scene(file);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": material.restitution: ", 0), 0u)
        << e.what();
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace drumlab
