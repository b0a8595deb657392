// One validation of a scene (engine/scene/scene_validation.hpp), whatever door the values come in
// by: a scene built in code names the same key the loader names in a file; a bridge volume whose
// rupture distance would become a search margin of many radii (a unit slip) is refused with the
// margin it would make; save_scene refuses what the loader would refuse and writes nothing; a
// restart refuses particles the scene cannot have made (exit 2, the dataset and row named).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "engine/contact/contact_model.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/restart_check.hpp"
#include "engine/scene/scene_validation.hpp"
#include "engine/scene/scene_writer.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

SceneConfig small_scene() {
  return parse_scene(output_scene_text(), "small.toml");
}

SceneConfig wet_scene() {
  return parse_scene(wet_output_scene_text(), "wet.toml");
}

std::string problem_key(const SceneConfig& s) {
  const auto p = scene_problem(s);
  return p ? p->key : std::string("(none)");
}

TEST(SceneValidation, EveryShippedSceneIsValid) {
  for (const auto& entry : std::filesystem::directory_iterator(DRUMLAB_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    const SceneConfig s = load_scene(entry.path());
    EXPECT_FALSE(scene_problem(s).has_value()) << scene_problem(s)->key;
  }
}

double nan_of() {
  return std::numeric_limits<double>::quiet_NaN();
}

TEST(SceneValidation, ValuesSetInCodeNameTheirKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* key;
    void (*edit)(SceneConfig&);
  };
  const Case cases[] = {
      {"material.restitution", [](SceneConfig& s) { s.material.restitution = 5.0; }},
      {"wall.friction", [](SceneConfig& s) { s.wall.friction = -1.0; }},
      {"drum.omega",
       [](SceneConfig& s) { s.drum.omega = std::numeric_limits<double>::infinity(); }},
      {"drum.diameter", [](SceneConfig& s) { s.drum.diameter = 0.01; }},
      {"particles[1].radius", [](SceneConfig& s) { s.classes[1].radius = -0.004; }},
      {"particles", [](SceneConfig& s) { s.classes[1].volume_fraction = 0.25; }},
      {"fill.count", [](SceneConfig& s) { s.fill.count = 0; }},
      {"fill.volume_fraction", [](SceneConfig& s) { s.fill.volume_fraction = 0.9; }},
      {"time.dt", [](SceneConfig& s) { s.time.dt = -1e-5; }},
      {"time.max_overlap", [](SceneConfig& s) { s.time.max_overlap = 1.5; }},
      {"performance.verlet_skin", [](SceneConfig& s) { s.performance.verlet_skin = 0.0; }},
      {"performance.pair_block_rows", [](SceneConfig& s) { s.performance.pair_block_rows = 0; }},
      {"search", [](SceneConfig& s) { s.search_method = "m9"; }},
      {"output.diagnostics_every", [](SceneConfig& s) { s.output.diagnostics_every = 0; }},
      {"contact.collision_time",
       [](SceneConfig& s) {
         s.contact.normal = NormalLaw::linear_viscoelastic;
         s.contact.collision_time = nan_of();
         s.contact.reference_radius = 0.002;
       }},
      {"contact.reference_radius",
       [](SceneConfig& s) {
         s.contact.normal = NormalLaw::linear_viscoelastic;
         s.contact.collision_time = 1e-3;
       }},
      {"contact.tangential_damping_ratio",
       [](SceneConfig& s) {
         s.contact.normal = NormalLaw::linear_viscoelastic;
         s.contact.collision_time = 1e-3;
         s.contact.reference_radius = 0.002;
         s.contact.tangential_damping_ratio = -0.1;
       }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.key);
    SceneConfig s = small_scene();
    c.edit(s);
    EXPECT_EQ(problem_key(s), c.key);
  }
  SceneConfig s = small_scene();
  s.drum.omega = nan;
  try {
    validate(s, "--edit 'omega=nan'");
    FAIL() << "accepted omega = nan";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "--edit 'omega=nan': drum.omega: must be a finite number (rad/s), got nan");
  }
}

TEST(SceneValidation, TheLoaderReportsTheValidationsKeyWithItsLine) {
  SmallDrumText t;
  t.restitution = "1.5";
  try {
    parse_scene(t.text(), "bad.toml");
    FAIL() << "accepted restitution 1.5";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("bad.toml: material.restitution: must be in (0, 1], got 1.5 (line ", 0), 0u)
        << m;
  }
}

// 5e-5 m^3 typed for 5e-11 m^3: s_rup = V^(1/3) = 0.037 m, 9 radii of 4 mm.
TEST(SceneValidation, ABridgeVolumeThatWouldMakeAHugeMarginIsRefused) {
  SceneConfig s = wet_scene();
  EXPECT_FALSE(scene_problem(s).has_value()) << "1e-9 m^3: s_rup = 1 mm = 0.25 radii";
  s.liquid.bridge_volume = 5e-5;
  const auto p = law_problem(s);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->key, "liquid.bridge_volume");
  EXPECT_NE(p->reason.find("0.0368 m = 9.21 smallest radii"), std::string::npos) << p->reason;
  EXPECT_THROW(ContactModel{s}, InputError) << "the contact model is a door too";
  // The bound: s_rup = 2 r_min = 8 mm, V = 5.12e-7 m^3 at a contact angle of 0.
  s.liquid.bridge_volume = 5.0e-7;
  EXPECT_FALSE(law_problem(s).has_value());
  s.liquid.bridge_volume = 5.3e-7;
  EXPECT_TRUE(law_problem(s).has_value());
  // With migration the largest bridge is the margin.
  SceneConfig m = wet_scene();
  m.liquid.migration = true;
  m.liquid.bridge_volume = 0.0;
  m.liquid.liquid_content = 0.05;
  m.liquid.max_bridge_volume = 5e-5;
  EXPECT_EQ(problem_key(m), "liquid.max_bridge_volume");
}

TEST(SceneValidation, SaveSceneRefusesWhatTheLoaderRefusesAndWritesNothing) {
  TempDir dir("validation-save");
  SceneConfig s = small_scene();
  s.material.restitution = 5.0;
  const auto file = dir.path() / "x.toml";
  try {
    save_scene(s, file);
    FAIL() << "saved restitution 5";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material.restitution"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(RestartCheck, ParticlesTheSceneCannotHaveMadeAreNamedByDatasetAndRow) {
  const SceneConfig scene = small_scene();
  const auto sim = settled_simulation(scene, 5);
  EXPECT_FALSE(restart_particles_problem(scene, sim->particles()).has_value());
  struct Case {
    const char* key;
    void (*damage)(Particles&);
  };
  const Case cases[] = {
      {"particles/mass: row 3", [](Particles& p) { p.mass[3] *= 2.0; }},
      {"particles/inv_mass: row 4", [](Particles& p) { p.inv_mass[4] = -p.inv_mass[4]; }},
      {"particles/radius: row 5", [](Particles& p) { p.radius[5] = 0.006; }},
      {"particles/inv_inertia: row 6", [](Particles& p) { p.inv_inertia[6] = 0.0; }},
      {"particles/size_class: row 7", [](Particles& p) { p.size_class[7] = 9; }},
      {"particles/velocity: row 8", [](Particles& p) { p.velocity[8].x() = NAN; }},
      {"particles/id: row 9", [](Particles& p) { p.id[9] = p.id[2]; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.key);
    SimulationState state = sim->state();
    c.damage(state.particles);
    const auto p = restart_particles_problem(scene, state.particles);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->key, c.key) << p->reason;
    EXPECT_THROW(Simulation(scene, std::move(state)), InputError);
  }
}

TEST(RestartCheck, ADamagedCheckpointIsExitTwoNamingTheDataset) {
  TempDir dir("restart-damaged");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const std::string good = (dir.path() / "good.h5").string();
  const std::string bad = (dir.path() / "bad.h5").string();
  auto r = run_cli("run " + scene + " --steps 20 --checkpoint " + good);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Checkpoint c = read_checkpoint(good);
  c.state.particles.mass[12] *= 1000.0;  // a heavy particle: unstable soon, were it run
  write_checkpoint(bad, c.state, c.scene_name);
  r = run_cli("run " + scene + " --restart " + bad + " --steps 20");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(bad + ": particles/mass: row 12:"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace drumlab::test
