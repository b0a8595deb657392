// The scene writer (engine/scene/scene_writer.hpp): every shipped scene and every key written loads
// back to the same SceneConfig, bit for bit; every field of SceneConfig changes the written text
// (the field table below fails to compile when a field is added without being listed); a failed
// save leaves no file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "engine/mesh/lifters.hpp"
#include "engine/mesh/stl_file.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/scene/scene_writer.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

/// Parses `scene`'s text under the same source name and expects the same config; prints both
/// texts when they differ (the difference shows as a differing line).
void expect_round_trip(const SceneConfig& scene) {
  const std::string text = scene_to_toml(scene);
  SceneConfig back;
  try {
    back = parse_scene(text, scene.source);
  } catch (const InputError& e) {
    ADD_FAILURE() << "written scene does not load: " << e.what() << "\n" << text;
    return;
  }
  EXPECT_TRUE(back == scene) << "written:\n" << text << "\nloads back as:\n" << scene_to_toml(back);
}

/// Every optional key set to a value other than its default (the random fill).
const char* const kEveryKey = R"(name = "every_key"
description = "every optional key, \"quoted\" and non-default"
gravity = [0.5, -9.0, 0.25]
search = "verlet:m3"

[drum]
diameter = 0.9
depth = 0.15
rpm = 7.0
tilt_deg = 17.3
ends = "periodic"

[[particles]]
name = "small"
radius = 0.005
volume_fraction = 0.3

[[particles]]
name = "large"
radius = 0.0123456789
volume_fraction = 0.7

[material]
density = 2600.0
youngs_modulus = 1.1e7
poisson_ratio = 0.25
restitution = 0.6
friction = 0.4
rolling_friction = 0.01

[wall]
youngs_modulus = 2e7
poisson_ratio = 0.2
restitution = 0.8
friction = 0.1
rolling_friction = 0.02

[contact]
normal = "linear"
linear_stiffness = 1e5

[liquid]
surface_tension = 0.072
contact_angle_deg = 20.0
bridge_volume = 1e-9

[fill]
kind = "random"
count = 1234
volume_fraction = 0.3
seed = 42
settle_time = 0.25

[time]
dt_factor = 0.15
duration = 1.5

[performance]
verlet_skin = 0.7
sort_every = 50
pair_block_rows = 1024

[output]
directory = "elsewhere/x"
diagnostics_every = 50
)";

/// The paper's packing, with an explicit dt and revolutions.
const char* const kPaperPacking = R"(name = "packing"
description = "paper packing"
[drum]
diameter = 2.0
depth = 0.2
omega = 1.0
[[particles]]
radius = 0.005
volume_fraction = 0.2
[[particles]]
radius = 0.01
volume_fraction = 0.3
[[particles]]
radius = 0.015
volume_fraction = 0.5
[material]
density = 2500.0
youngs_modulus = 5e6
poisson_ratio = 0.3
restitution = 0.5
friction = 0.5
[fill]
kind = "paper_packing"
box = [0.3, 0.2, 0.1]
[time]
dt = 2e-5
revolutions = 0.5
)";

/// A file fill; the CSV lies beside the scene ("packing.csv").
const char* const kFileFill = R"(name = "from_file"
[drum]
diameter = 0.5
depth = 0.1
omega = 1.0
[[particles]]
radius = 0.01
[material]
density = 2500.0
youngs_modulus = 5e6
poisson_ratio = 0.3
restitution = 0.5
friction = 0.5
[fill]
kind = "file"
file = "packing.csv"
settle_time = 0.1
[time]
duration = 0.2
)";

const char* const kCsv = "x,y,z,r\n0,-0.1,0.05,0.01\n";

TEST(SceneWriter, EveryShippedSceneRoundTrips) {
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(DRUMLAB_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    expect_round_trip(load_scene(entry.path()));
    ++scenes;
  }
  EXPECT_GE(scenes, 10);
}

TEST(SceneWriter, EveryOptionalKeyRoundTrips) {
  const SceneConfig scene = parse_scene(kEveryKey, "every_key.toml");
  ASSERT_TRUE(scene.liquid.enabled);
  ASSERT_NE(scene.wall, scene.material);
  expect_round_trip(scene);
  expect_round_trip(parse_scene(kPaperPacking, "packing.toml"));
  TempDir dir("scene-writer-keys");
  dir.write("packing.csv", kCsv);
  expect_round_trip(parse_scene(kFileFill, (dir.path() / "from_file.toml").string()));
}

TEST(SceneWriter, NumbersAreShortAndExact) {
  const SceneConfig scene = parse_scene(kEveryKey, "every_key.toml");
  const std::string text = scene_to_toml(scene);
  EXPECT_NE(text.find("radius = 0.0123456789\n"), std::string::npos) << text;
  EXPECT_NE(text.find("tilt_deg = 17.3\n"), std::string::npos) << text;
  EXPECT_NE(text.find("density = 2600.0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("bridge_volume = 1e-09\n"), std::string::npos) << text;
  // Defaults of [wall] are the material's: only the differing keys are written.
  SceneConfig same_wall = scene;
  same_wall.wall = same_wall.material;
  EXPECT_EQ(scene_to_toml(same_wall).find("[wall]"), std::string::npos);
}

TEST(SceneWriter, TiltInDegreesIsTheShortestExactDecimal) {
  for (int tenth = 0; tenth < 900; ++tenth) {
    const double degrees = tenth / 10.0;
    const double radians = tilt_from_degrees(degrees);
    EXPECT_EQ(tilt_from_degrees(tilt_in_degrees(radians)), radians) << degrees;
    EXPECT_EQ(tilt_in_degrees(radians), degrees) << degrees;
  }
}

TEST(SceneWriter, FilePathIsRelativeToTheSavedScene) {
  TempDir dir("scene-writer-path");
  fs::create_directories(dir.path() / "data");
  fs::create_directories(dir.path() / "scenes");
  dir.write("data/packing.csv", kCsv);
  std::string text = kFileFill;
  text.replace(text.find("\"packing.csv\""), 13, "\"../data/packing.csv\"");
  const SceneConfig scene = parse_scene(text, (dir.path() / "scenes" / "a.toml").string());
  EXPECT_EQ(scene.fill.file, dir.path() / "data" / "packing.csv");

  // Saved elsewhere: the path is written relative to the new folder and loads the same file.
  fs::create_directories(dir.path() / "saved" / "deeper");
  const fs::path saved = dir.path() / "saved" / "deeper" / "b.toml";
  save_scene(scene, saved);
  std::ifstream in(saved);
  const std::string written((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(written.find("file = \"../../data/packing.csv\""), std::string::npos) << written;
  SceneConfig back = load_scene(saved);
  EXPECT_EQ(back.source, saved.string());
  back.source = scene.source;
  EXPECT_TRUE(back == scene) << written;

  // The whole tree moved: the relative path still finds the CSV.
  const fs::path moved = dir.path().string() + "-moved";
  fs::remove_all(moved);
  fs::rename(dir.path(), moved);
  const SceneConfig from_moved = load_scene(moved / "saved" / "deeper" / "b.toml");
  EXPECT_EQ(from_moved.fill.file, moved / "data" / "packing.csv");
  fs::rename(moved, dir.path());
}

TEST(SceneWriter, UnwritablePathIsOneLineAndLeavesNoFile) {
  const SceneConfig scene = parse_scene(kEveryKey, "every_key.toml");
  TempDir dir("scene-writer-bad");
  const fs::path missing_folder = dir.path() / "no_such_folder" / "s.toml";
  const fs::path is_a_folder = dir.path() / "a_folder";
  fs::create_directories(is_a_folder);
  for (const fs::path& file : {missing_folder, is_a_folder}) {
    SCOPED_TRACE(file.string());
    std::string message;
    try {
      save_scene(scene, file);
    } catch (const InputError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(missing_folder));
  EXPECT_TRUE(fs::is_directory(is_a_folder));
  // Nothing else left behind (no temporary).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
  EXPECT_TRUE(fs::is_empty(is_a_folder));
}

TEST(SceneWriter, SeedBeyondTomlIntegersIsRefusedNamingTheKey) {
  SceneConfig scene = parse_scene(kEveryKey, "every_key.toml");
  scene.fill.seed = ~std::uint64_t{0};
  TempDir dir("scene-writer-seed");
  const fs::path file = dir.path() / "s.toml";
  try {
    save_scene(scene, file);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fill.seed"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file));
}

// ---- every field is written ----------------------------------------------------------------

/// The number of fields of each config struct, checked by a structured binding: adding a field
/// makes this fail to compile. Then give the field a setter in `field_setters()`, write it in
/// engine/scene/scene_writer.cpp and raise its count here.
constexpr int kSceneFields = 19, kMeshFields = 8, kLifterFields = 9, kMeshMaterialFields = 5,
              kDrumFields = 6, kOrbitFields = 4, kClassFields = 8, kMaterialFields = 6,
              kContactFields = 9, kLiquidFields = 16, kCohesionFields = 2, kSprayFields = 12,
              kFillFields = 7, kTimeFields = 5, kPerformanceFields = 3, kOutputFields = 2;

[[maybe_unused]] void field_counts(const SceneConfig& s) {
  [[maybe_unused]] const auto& [name, source, description, gravity, drum, classes, material, wall,
                                meshes, lifters, contact, liquid, cohesion, sprays, fill, time,
                                search, performance, output] = s;
  [[maybe_unused]] const auto& [mesh_file, scale, offset, rotation, attach, smooth, closed,
                                mesh_material] = s.meshes.front();
  [[maybe_unused]] const auto& [lifter_count, height, length, thickness, lifter_shape, lifter_angle,
                                tip, phase_deg, lifter_material] = s.lifters.front();
  [[maybe_unused]] const auto& [mesh_youngs, mesh_poisson, mesh_restitution, mesh_friction,
                                mesh_rolling] = s.meshes.front().material;
  [[maybe_unused]] const auto& [diameter, depth, omega, tilt, ends, orbit] = s.drum;
  [[maybe_unused]] const auto& [orbit_radius, orbit_omega, phase, speed_ratio] = s.drum.orbit;
  [[maybe_unused]] const auto& [class_name, radius, class_fraction, distribution, radius_sigma,
                                truncate, radii, shares, class_liquid] = s.classes.front();
  [[maybe_unused]] const auto& [density, youngs, poisson, restitution, friction, rolling] =
      s.material;
  [[maybe_unused]] const auto& [normal, stiffness, collision_time, reference_radius,
                                tangential_stiffness, tangential_damping, rolling_law,
                                rolling_stiffness, rolling_damping] = s.contact;
  [[maybe_unused]] const auto& [enabled, tension, angle, volume, migration, content, film_share,
                                max_volume, film_radius, proportional_draw, rupture_share,
                                viscosity, min_gap, wall_bridges, wall_tension, wall_angle] =
      s.liquid;
  [[maybe_unused]] const auto& [cohesive, energy_density] = s.cohesion;
  [[maybe_unused]] const auto& [spray_name, position, direction, shape, angle_deg, fan_axis, rate,
                                start, stop, droplet_radius, droplet_speed, at_wall] =
      s.sprays.front();
  [[maybe_unused]] const auto& [kind, count, fraction, seed, settle, box, file] = s.fill;
  [[maybe_unused]] const auto& [dt, dt_factor, duration, revolutions, max_overlap] = s.time;
  [[maybe_unused]] const auto& [skin, sort_every, pair_block_rows] = s.performance;
  [[maybe_unused]] const auto& [directory, diagnostics] = s.output;
}

enum class Base { every_key, paper_packing, file_fill, spray, meshes };

struct FieldSetter {
  std::string field;  ///< "struct.field" (the struct's scene table, or "scene" for the top level)
  Base base;
  std::function<void(SceneConfig&)> set;
};

/// Liquid given as a content with films (migration) instead of one bridge volume.
void migrate(SceneConfig& s, double content, double max_bridge_volume) {
  s.liquid.migration = true;
  s.liquid.bridge_volume = 0.0;
  s.liquid.liquid_content = content;
  s.liquid.max_bridge_volume = max_bridge_volume;
}

/// kEveryKey with films (content 0: a dry powder) and a flat-fan nozzle of binder.
SceneConfig spray_scene() {
  SceneConfig s = parse_scene(kEveryKey, "every_key.toml");
  migrate(s, 0.0, 1e-9);
  SprayConfig c;
  c.name = "nozzle";
  c.position = Vec3(0.01, 0.2, 0.075);
  c.direction = Vec3(0.0, -1.0, 0.0);
  c.shape = SprayShape::flat_fan;
  c.angle_deg = 60.0;
  c.fan_axis = Vec3(0.0, 0.0, 1.0);
  c.rate = 1e-7;
  c.start = 0.5;
  c.stop = 2.0;
  c.droplet_radius = 1e-4;
  c.droplet_speed = 2.0;
  s.sprays.push_back(c);
  return s;
}

/// The normal law set by a collision time and a restitution (linear_viscoelastic.hpp).
void linear_viscoelastic(SceneConfig& s, double collision_time, double reference_radius) {
  s.contact.normal = NormalLaw::linear_viscoelastic;
  s.contact.linear_stiffness = 0.0;
  s.contact.collision_time = collision_time;
  s.contact.reference_radius = reference_radius;
}

/// A small drum with a box from an STL file and generated lifters, in `dir` (box.stl there).
SceneConfig mesh_scene(const fs::path& dir) {
  write_stl(make_mesh(box_triangles(Vec3(0.0, -0.05, 0.025), Vec3::UnitX(), Vec3::UnitY(),
                                    Vec3(0.01, 0.01, 0.01)),
                      0.3, "box"),
            dir / "box.stl");
  return parse_scene(R"(
[drum]
diameter = 0.2
depth = 0.05
omega = 2.0
[[particles]]
radius = 0.004
volume_fraction = 1.0
[material]
density = 2500.0
youngs_modulus = 5e6
poisson_ratio = 0.3
restitution = 0.5
friction = 0.5
[[wall.mesh]]
file = "box.stl"
[[wall.lifters]]
count = 4
height = 0.02
[fill]
count = 100
[time]
duration = 0.1
)",
                     (dir / "meshes.toml").string());
}

std::vector<FieldSetter> field_setters(const fs::path& other_csv, const fs::path& other_stl) {
  using B = Base;
  return {
      {"scene.name", B::every_key, [](SceneConfig& s) { s.name = "renamed"; }},
      {"scene.description", B::every_key,
       [](SceneConfig& s) { s.description = "tab\t, newline\n, quote \", backslash \\, µm"; }},
      {"scene.gravity", B::every_key, [](SceneConfig& s) { s.gravity.z() = 0.125; }},
      {"scene.search_method", B::every_key, [](SceneConfig& s) { s.search_method = "mlgrid"; }},
      {"drum.diameter", B::every_key, [](SceneConfig& s) { s.drum.diameter = 0.95; }},
      {"drum.depth", B::every_key, [](SceneConfig& s) { s.drum.depth = 0.2; }},
      {"drum.omega", B::every_key, [](SceneConfig& s) { s.drum.omega = 0.1 + 0.2; }},
      {"drum.tilt", B::every_key, [](SceneConfig& s) { s.drum.tilt = tilt_from_degrees(45.0); }},
      {"drum.ends", B::every_key, [](SceneConfig& s) { s.drum.ends = DrumEnds::caps; }},
      {"drum.orbit.radius", B::every_key,
       [](SceneConfig& s) {
         s.drum.tilt = 0.0;
         s.drum.orbit.radius = 0.4;
         s.drum.orbit.omega = 3.0;
       }},
      {"drum.orbit.omega", B::every_key,
       [](SceneConfig& s) {
         s.drum.tilt = 0.0;
         s.drum.orbit.radius = 0.3;
         s.drum.orbit.omega = -2.5;
       }},
      {"drum.orbit.phase", B::every_key,
       [](SceneConfig& s) {
         s.drum.tilt = 0.0;
         s.drum.orbit = {0.3, 3.0, tilt_from_degrees(40.0), std::nullopt};
       }},
      {"drum.orbit.speed_ratio", B::every_key,
       [](SceneConfig& s) {
         s.drum.tilt = 0.0;
         s.drum.orbit = {0.3, 3.0, 0.0, -2.5};
         s.drum.omega = 3.0 * (1.0 - 2.5);
       }},
      {"classes.name", B::every_key, [](SceneConfig& s) { s.classes[0].name = "tiny"; }},
      {"classes.radius", B::every_key, [](SceneConfig& s) { s.classes[0].radius = 0.004; }},
      {"classes.distribution", B::every_key,
       [](SceneConfig& s) {
         s.classes[0].distribution = SizeKind::lognormal;
         s.classes[0].radius_sigma = 0.0015;
       }},
      {"classes.radius_sigma", B::every_key,
       [](SceneConfig& s) {
         s.classes[0].distribution = SizeKind::normal;
         s.classes[0].radius_sigma = 0.1 * 0.005;
       }},
      {"classes.truncate", B::every_key,
       [](SceneConfig& s) {
         s.classes[1].distribution = SizeKind::normal;
         s.classes[1].radius_sigma = 0.001;
         s.classes[1].truncate = 2.5;
       }},
      {"classes.radii", B::every_key,
       [](SceneConfig& s) {
         s.classes[0].distribution = SizeKind::table;
         s.classes[0].radius = 0.0;
         s.classes[0].radii = {0.003, 0.0041, 0.005};
         s.classes[0].shares = {1.0, 2.0, 1.0};
       }},
      {"classes.shares", B::every_key,
       [](SceneConfig& s) {
         s.classes[1].distribution = SizeKind::table;
         s.classes[1].radius = 0.0;
         s.classes[1].radii = {0.01};
         s.classes[1].shares = {0.3};
       }},
      {"classes.volume_fraction", B::every_key,
       [](SceneConfig& s) {
         s.classes[0].volume_fraction = 0.25;
         s.classes[1].volume_fraction = 0.75;
       }},
      // The loader gives the wall the material's density (the wall has no density key).
      {"material.density", B::every_key,
       [](SceneConfig& s) { s.material.density = s.wall.density = 2700.0; }},
      {"material.youngs_modulus", B::every_key,
       [](SceneConfig& s) { s.material.youngs_modulus = 3e6; }},
      {"material.poisson_ratio", B::every_key,
       [](SceneConfig& s) { s.material.poisson_ratio = 0.35; }},
      {"material.restitution", B::every_key, [](SceneConfig& s) { s.material.restitution = 0.9; }},
      {"material.friction", B::every_key, [](SceneConfig& s) { s.material.friction = 0.0; }},
      {"material.rolling_friction", B::every_key,
       [](SceneConfig& s) { s.material.rolling_friction = 0.05; }},
      // The wall's density is not a key (the wall has none): five wall fields.
      {"wall.youngs_modulus", B::every_key, [](SceneConfig& s) { s.wall.youngs_modulus = 4e7; }},
      {"wall.poisson_ratio", B::every_key, [](SceneConfig& s) { s.wall.poisson_ratio = 0.1; }},
      {"wall.restitution", B::every_key, [](SceneConfig& s) { s.wall.restitution = 0.7; }},
      {"wall.friction", B::every_key, [](SceneConfig& s) { s.wall.friction = 0.3; }},
      {"wall.rolling_friction", B::every_key,
       [](SceneConfig& s) { s.wall.rolling_friction = 0.0; }},
      {"contact.normal", B::every_key,
       [](SceneConfig& s) {
         s.contact.normal = NormalLaw::hertz;
         s.contact.linear_stiffness = 0.0;
       }},
      {"contact.linear_stiffness", B::every_key,
       [](SceneConfig& s) { s.contact.linear_stiffness = 2.5e5; }},
      {"contact.collision_time", B::every_key,
       [](SceneConfig& s) { linear_viscoelastic(s, 1e-3 / 3.0, 0.01); }},
      {"contact.reference_radius", B::every_key,
       [](SceneConfig& s) { linear_viscoelastic(s, 1e-3, 0.1 / 7.0); }},
      {"contact.tangential_stiffness_ratio", B::every_key,
       [](SceneConfig& s) {
         linear_viscoelastic(s, 1e-3, 0.01);
         s.contact.tangential_stiffness_ratio = 0.4;
       }},
      {"contact.tangential_damping_ratio", B::every_key,
       [](SceneConfig& s) {
         linear_viscoelastic(s, 1e-3, 0.01);
         s.contact.tangential_damping_ratio = 0.0;
       }},
      {"contact.rolling", B::every_key,
       [](SceneConfig& s) {
         linear_viscoelastic(s, 1e-3, 0.01);
         s.contact.rolling = RollingLaw::spring;
       }},
      {"contact.rolling_stiffness_ratio", B::every_key,
       [](SceneConfig& s) {
         linear_viscoelastic(s, 1e-3, 0.01);
         s.contact.rolling = RollingLaw::spring;
         s.contact.rolling_stiffness_ratio = 0.3;
       }},
      {"contact.rolling_damping_ratio", B::every_key,
       [](SceneConfig& s) {
         linear_viscoelastic(s, 1e-3, 0.01);
         s.contact.rolling = RollingLaw::spring;
         s.contact.rolling_damping_ratio = 0.0;
       }},
      {"spray.name", B::spray, [](SceneConfig& s) { s.sprays[0].name = "other"; }},
      {"spray.position", B::spray, [](SceneConfig& s) { s.sprays[0].position.x() = -0.02; }},
      {"spray.direction", B::spray, [](SceneConfig& s) { s.sprays[0].direction.x() = 0.5; }},
      {"spray.shape", B::spray,
       [](SceneConfig& s) {
         s.sprays[0].shape = SprayShape::cone;
         s.sprays[0].fan_axis = SprayConfig{}.fan_axis;  // a cone writes none
       }},
      {"spray.angle_deg", B::spray, [](SceneConfig& s) { s.sprays[0].angle_deg = 12.5; }},
      {"spray.fan_axis", B::spray, [](SceneConfig& s) { s.sprays[0].fan_axis.x() = 1.0; }},
      {"spray.rate", B::spray, [](SceneConfig& s) { s.sprays[0].rate = 3e-8; }},
      {"spray.start", B::spray, [](SceneConfig& s) { s.sprays[0].start = 0.75; }},
      {"spray.stop", B::spray,
       [](SceneConfig& s) { s.sprays[0].stop = std::numeric_limits<double>::infinity(); }},
      {"spray.droplet_radius", B::spray, [](SceneConfig& s) { s.sprays[0].droplet_radius = 5e-5; }},
      {"spray.droplet_speed", B::spray, [](SceneConfig& s) { s.sprays[0].droplet_speed = 0.0; }},
      {"spray.at_wall", B::spray, [](SceneConfig& s) { s.sprays[0].at_wall = SprayAtWall::wet; }},
      {"mesh.file", B::meshes, [other_stl](SceneConfig& s) { s.meshes[0].file = other_stl; }},
      {"mesh.scale", B::meshes, [](SceneConfig& s) { s.meshes[0].scale = 0.5; }},
      {"mesh.offset", B::meshes, [](SceneConfig& s) { s.meshes[0].offset.z() = 0.005; }},
      {"mesh.rotation_deg", B::meshes, [](SceneConfig& s) { s.meshes[0].rotation_deg.y() = 12.5; }},
      {"mesh.attach", B::meshes, [](SceneConfig& s) { s.meshes[0].attach = MeshAttach::lab; }},
      {"mesh.smooth_angle_deg", B::meshes,
       [](SceneConfig& s) { s.meshes[0].smooth_angle_deg = 45.0; }},
      {"mesh.closed", B::meshes, [](SceneConfig& s) { s.meshes[0].closed = true; }},
      {"mesh.material.youngs_modulus", B::meshes,
       [](SceneConfig& s) { s.meshes[0].material.youngs_modulus = 7e7; }},
      {"mesh.material.poisson_ratio", B::meshes,
       [](SceneConfig& s) { s.meshes[0].material.poisson_ratio = 0.2; }},
      {"mesh.material.restitution", B::meshes,
       [](SceneConfig& s) { s.meshes[0].material.restitution = 0.8; }},
      {"mesh.material.friction", B::meshes,
       [](SceneConfig& s) { s.meshes[0].material.friction = 0.25; }},
      {"mesh.material.rolling_friction", B::meshes,
       [](SceneConfig& s) { s.meshes[0].material.rolling_friction = 0.01; }},
      {"lifters.count", B::meshes, [](SceneConfig& s) { s.lifters[0].count = 6; }},
      {"lifters.height", B::meshes, [](SceneConfig& s) { s.lifters[0].height = 0.015; }},
      {"lifters.length", B::meshes, [](SceneConfig& s) { s.lifters[0].length = 0.04; }},
      {"lifters.thickness", B::meshes, [](SceneConfig& s) { s.lifters[0].thickness = 0.003; }},
      {"lifters.shape", B::meshes, [](SceneConfig& s) { s.lifters[0].shape = LifterKind::angled; }},
      {"lifters.angle_deg", B::meshes,
       [](SceneConfig& s) {
         s.lifters[0].shape = LifterKind::angled;
         s.lifters[0].angle_deg = 60.0;
       }},
      {"lifters.tip", B::meshes,
       [](SceneConfig& s) {
         s.lifters[0].shape = LifterKind::angled;
         s.lifters[0].tip = 0.008;
       }},
      {"lifters.phase_deg", B::meshes, [](SceneConfig& s) { s.lifters[0].phase_deg = 22.5; }},
      {"lifters.material.youngs_modulus", B::meshes,
       [](SceneConfig& s) { s.lifters[0].material.youngs_modulus = 7e7; }},
      {"lifters.material.poisson_ratio", B::meshes,
       [](SceneConfig& s) { s.lifters[0].material.poisson_ratio = 0.2; }},
      {"lifters.material.restitution", B::meshes,
       [](SceneConfig& s) { s.lifters[0].material.restitution = 0.8; }},
      {"lifters.material.friction", B::meshes,
       [](SceneConfig& s) { s.lifters[0].material.friction = 0.25; }},
      {"lifters.material.rolling_friction", B::meshes,
       [](SceneConfig& s) { s.lifters[0].material.rolling_friction = 0.01; }},
      {"liquid.enabled", B::every_key, [](SceneConfig& s) { s.liquid = LiquidConfig{}; }},
      {"liquid.surface_tension", B::every_key,
       [](SceneConfig& s) { s.liquid.surface_tension = 0.05; }},
      {"liquid.contact_angle_deg", B::every_key,
       [](SceneConfig& s) { s.liquid.contact_angle_deg = 0.0; }},
      {"liquid.bridge_volume", B::every_key, [](SceneConfig& s) { s.liquid.bridge_volume = 3e-9; }},
      {"liquid.migration", B::every_key, [](SceneConfig& s) { migrate(s, 0.05, 1e-9); }},
      {"liquid.liquid_content", B::every_key, [](SceneConfig& s) { migrate(s, 0.02, 1e-9); }},
      {"particles.liquid_content", B::every_key,
       [](SceneConfig& s) {
         migrate(s, 0.05, 1e-9);
         s.classes[0].liquid_content = 0.3;
       }},
      {"liquid.film_share", B::every_key,
       [](SceneConfig& s) {
         migrate(s, 0.05, 1e-9);
         s.liquid.film_share = 0.75;
       }},
      {"liquid.max_bridge_volume", B::every_key, [](SceneConfig& s) { migrate(s, 0.05, 4e-9); }},
      {"liquid.film_radius", B::every_key,
       [](SceneConfig& s) {
         migrate(s, 0.05, 1e-9);
         s.liquid.film_radius = 0.1 / 3.0;
       }},
      {"liquid.proportional_draw", B::every_key,
       [](SceneConfig& s) {
         migrate(s, 0.05, 1e-9);
         s.liquid.proportional_draw = true;
       }},
      {"liquid.rupture_to_bridges", B::every_key,
       [](SceneConfig& s) {
         migrate(s, 0.05, 1e-9);
         s.liquid.rupture_to_bridges = 0.75;
       }},
      {"liquid.viscosity", B::every_key,
       [](SceneConfig& s) {
         s.liquid.viscosity = 1e-3;
         s.liquid.min_gap = 1e-6;
       }},
      {"liquid.min_gap", B::every_key,
       [](SceneConfig& s) {
         s.liquid.viscosity = 2e-3;
         s.liquid.min_gap = 3e-6;
       }},
      {"liquid.wall_bridges", B::every_key, [](SceneConfig& s) { s.liquid.wall_bridges = false; }},
      {"liquid.wall_surface_tension", B::every_key,
       [](SceneConfig& s) { s.liquid.wall_surface_tension = 0.03; }},
      {"liquid.wall_contact_angle_deg", B::every_key,
       [](SceneConfig& s) { s.liquid.wall_contact_angle_deg = 45.0; }},
      {"cohesion.enabled", B::every_key, [](SceneConfig& s) { s.cohesion.enabled = true; }},
      {"cohesion.energy_density", B::every_key,
       [](SceneConfig& s) {
         s.cohesion.enabled = true;
         s.cohesion.energy_density = 2.5e4;
       }},
      {"fill.kind", B::file_fill,
       [](SceneConfig& s) {
         s.fill.kind = FillKind::random;
         s.fill.count = 10;
         s.fill.file.clear();
       }},
      {"fill.count", B::every_key, [](SceneConfig& s) { s.fill.count = 99; }},
      {"fill.volume_fraction", B::every_key, [](SceneConfig& s) { s.fill.volume_fraction = 0.5; }},
      {"fill.seed", B::every_key, [](SceneConfig& s) { s.fill.seed = 0; }},
      {"fill.settle_time", B::file_fill, [](SceneConfig& s) { s.fill.settle_time = 0.0; }},
      {"fill.box", B::paper_packing, [](SceneConfig& s) { s.fill.box.y() = 0.4; }},
      {"fill.file", B::file_fill, [other_csv](SceneConfig& s) { s.fill.file = other_csv; }},
      {"time.dt", B::paper_packing, [](SceneConfig& s) { s.time.dt.reset(); }},
      {"time.dt_factor", B::every_key, [](SceneConfig& s) { s.time.dt_factor = 0.5; }},
      {"time.duration", B::every_key, [](SceneConfig& s) { s.time.duration = 2.0 / 3.0; }},
      {"time.revolutions", B::paper_packing, [](SceneConfig& s) { s.time.revolutions = 1e-3; }},
      {"time.max_overlap", B::every_key, [](SceneConfig& s) { s.time.max_overlap = 0.75; }},
      {"performance.verlet_skin", B::every_key,
       [](SceneConfig& s) { s.performance.verlet_skin = 0.3; }},
      {"performance.sort_every", B::every_key,
       [](SceneConfig& s) { s.performance.sort_every = 0; }},
      {"performance.pair_block_rows", B::every_key,
       [](SceneConfig& s) { s.performance.pair_block_rows = 4096; }},
      {"output.directory", B::every_key, [](SceneConfig& s) { s.output.directory = "o u t"; }},
      {"output.diagnostics_every", B::every_key,
       [](SceneConfig& s) { s.output.diagnostics_every = 1; }},
  };
}

TEST(SceneWriter, EveryFieldChangesTheTextAndRoundTrips) {
  TempDir dir("scene-writer-fields");
  dir.write("packing.csv", kCsv);
  const fs::path other_csv = dir.write("other.csv", kCsv);
  const SceneConfig bases[] = {parse_scene(kEveryKey, "every_key.toml"),
                               parse_scene(kPaperPacking, "packing.toml"),
                               parse_scene(kFileFill, (dir.path() / "from_file.toml").string()),
                               spray_scene(), mesh_scene(dir.path())};
  fs::copy_file(dir.path() / "box.stl", dir.path() / "other.stl");
  const auto setters = field_setters(other_csv, dir.path() / "other.stl");
  for (const FieldSetter& setter : setters) {
    SCOPED_TRACE(setter.field);
    const SceneConfig& base = bases[static_cast<int>(setter.base)];
    SceneConfig changed = base;
    setter.set(changed);
    ASSERT_FALSE(changed == base) << "test bug: the setter changes nothing";
    EXPECT_NE(scene_to_toml(changed), scene_to_toml(base));
    expect_round_trip(changed);
  }
  // One setter per field (`source` is where the scene came from, not a key; the wall's density is
  // unused); the counts are those of field_counts above.
  auto count = [&](std::string_view prefix) {
    return std::count_if(setters.begin(), setters.end(),
                         [&](const FieldSetter& s) { return s.field.starts_with(prefix); });
  };
  EXPECT_EQ(count("scene."), kSceneFields - 15);  // name, description, gravity, search
  EXPECT_EQ(count("mesh."), kMeshFields - 1 + kMeshMaterialFields);
  EXPECT_EQ(count("lifters."), kLifterFields - 1 + kMeshMaterialFields);
  EXPECT_EQ(count("drum."), kDrumFields - 1 + kOrbitFields);
  EXPECT_EQ(count("classes."), kClassFields);
  EXPECT_EQ(count("material."), kMaterialFields);
  EXPECT_EQ(count("wall."), kMaterialFields - 1);
  EXPECT_EQ(count("contact."), kContactFields);
  EXPECT_EQ(count("liquid."), kLiquidFields);
  EXPECT_EQ(count("cohesion."), kCohesionFields);
  EXPECT_EQ(count("spray."), kSprayFields);
  EXPECT_EQ(count("fill."), kFillFields);
  EXPECT_EQ(count("time."), kTimeFields);
  EXPECT_EQ(count("performance."), kPerformanceFields);
  EXPECT_EQ(count("output."), kOutputFields);
}

TEST(SceneWriter, AddingAClassIsWritten) {
  const SceneConfig base = parse_scene(kEveryKey, "every_key.toml");
  SceneConfig changed = base;
  changed.classes[1].volume_fraction = 0.5;
  changed.classes.push_back({"third", 0.02, 0.2});
  expect_round_trip(changed);
}

}  // namespace
}  // namespace drumlab
