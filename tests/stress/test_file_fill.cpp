// [fill] kind = "file": the user's own packing, validated against the scene, and the documented
// overlap policy (refuse above kMaxFileOverlap of the smaller radius; smaller overlaps are pushed
// apart by the contact law with a speed bounded by the stored elastic energy).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "engine/fill/file_fill.hpp"
#include "engine/io/particle_csv.hpp"
#include "engine/simulation.hpp"
#include "tests/small_drum_text.hpp"

namespace drumlab {
namespace {

constexpr double kR = 0.004;

std::string scene_text(const std::string& fill, double restitution = 0.5,
                       const std::string& gravity = "[0.0, -9.81, 0.0]") {
  test::SmallDrumText t;
  t.gravity = gravity;
  t.diameter = "0.1";
  t.depth = "0.025";
  t.omega = "1.0";
  t.restitution = std::to_string(restitution);
  t.fill = fill;
  t.time = "dt_factor = 0.02\nduration = 0.01";
  return t.text();
}

SceneConfig random_scene() {
  return parse_scene(scene_text("count = 10"), "s.toml");
}

std::string error_of(const std::string& csv) {
  try {
    particles_from_table(random_scene(), parse_particle_csv(csv, "p.csv"), "p.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FileFill, TakesPositionsVelocitiesAndClasses) {
  const ParticleTable t = parse_particle_csv(
      "x,y,z,r,vx,vy,vz\n0,-0.02,0.01,0.004,1,2,3\n0.02,-0.02,0.012,0.008,0,0,-1\n", "p.csv");
  ASSERT_EQ(t.velocity.size(), 2u);
  EXPECT_EQ(t.line, (std::vector<std::size_t>{2, 3}));
  const Particles p = particles_from_table(random_scene(), t, "p.csv");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p.size_class[0], 0);
  EXPECT_EQ(p.size_class[1], 1);
  EXPECT_EQ(p.velocity[0], Vec3(1, 2, 3));
  EXPECT_EQ(p.velocity[1], Vec3(0, 0, -1));
  EXPECT_EQ(p.position[1], Vec3(0.02, -0.02, 0.012));
  EXPECT_NEAR(p.mass[1], 2500.0 * 4.0 / 3.0 * M_PI * 0.008 * 0.008 * 0.008, 1e-12);
}

TEST(FileFill, RefusesBadPackingsNamingTheLine) {
  EXPECT_NE(error_of("x,y,z,r\n").find("no particles"), std::string::npos);
  EXPECT_NE(error_of("x,y,z,r\n0,-0.02,0.01,0.005\n").find("p.csv:2: radius 0.005"),
            std::string::npos);
  EXPECT_NE(error_of("x,y,z,r\n0,0,0.01,0.004\n1e300,0,0.01,0.004\n").find("p.csv:3:"),
            std::string::npos);
  EXPECT_NE(error_of("x,y,z,r\n0,0,-0.01,0.004\n").find("outside the drum"), std::string::npos);
  // Centre inside, but 0.25 r into the mantle (R = 0.05): above the 10 % limit.
  EXPECT_NE(error_of("x,y,z,r\n0.047,0,0.01,0.004\n").find("drum wall"), std::string::npos);
  EXPECT_NE(error_of("x,y,z,r,vx,vy\n0,0,0.01,0.004,1,1\n").find("vx, vy, vz"), std::string::npos);
}

TEST(FileFill, OverlapPolicyRefusesAboveTenPercentNamingBothLines) {
  // Centres 2r - d apart: overlap d. 0.12 r is refused, 0.08 r accepted.
  const auto csv = [](double overlap) {
    return "x,y,z,r\n0,0,0.0125,0.004\n" + std::to_string(2 * kR - overlap * kR) +
           ",0,0.0125,0.004\n";
  };
  const std::string e = error_of(csv(0.12));
  EXPECT_NE(e.find("p.csv:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("line 2"), std::string::npos) << e;
  EXPECT_NE(e.find("0.12 of the smaller radius"), std::string::npos) << e;
  EXPECT_EQ(error_of(csv(0.08)), "");
}

/// Two equal spheres overlapping by 0.08 r in zero gravity. The stored Hertz energy
/// E0 = 8/15 E* sqrt(R*) d^(5/2) (E* = E / (2 (1 - nu^2)), R* = r / 2) bounds the separation
/// speed: v_rel <= sqrt(2 E0 / m_eff), reached (within 2 %, dt = 0.02 t_Rayleigh) when e = 1.
double release_speed(double restitution, double* bound) {
  const double overlap = 0.08 * kR;
  const SceneConfig scene =
      parse_scene(scene_text("count = 2", restitution, "[0.0, 0.0, 0.0]"), "s.toml");
  ParticleTable t;
  t.position = {Vec3(-kR + 0.5 * overlap, 0, 0.0125), Vec3(kR - 0.5 * overlap, 0, 0.0125)};
  t.radius = {kR, kR};
  t.line = {2, 3};
  Simulation sim(scene, particles_from_table(scene, t, "p.csv"));
  const double e_star = 5e6 / (2.0 * (1.0 - 0.3 * 0.3));
  const double e0 = 8.0 / 15.0 * e_star * std::sqrt(0.5 * kR) * std::pow(overlap, 2.5);
  const double m_eff = 0.5 * sim.particles().mass[0];
  *bound = std::sqrt(2.0 * e0 / m_eff);
  EXPECT_NEAR(sim.diagnostics().elastic_energy, e0, 1e-12 * e0);
  sim.advance(static_cast<std::uint64_t>(0.003 / sim.dt()));  // ~10 contact times, no wall yet
  EXPECT_EQ(sim.diagnostics().contacts, 0u) << "overlap not resolved";
  return (sim.particles().velocity[1] - sim.particles().velocity[0]).norm();
}

TEST(FileFill, SmallOverlapIsReleasedWithBoundedSpeed) {
  double bound = 0.0;
  const double elastic = release_speed(1.0, &bound);
  EXPECT_NEAR(elastic, bound, 0.02 * bound);
  const double damped = release_speed(0.5, &bound);
  EXPECT_GT(damped, 0.1 * bound);
  EXPECT_LT(damped, 0.9 * bound);  // damping takes energy
}

TEST(FileFill, SceneKeyReadsPathRelativeToTheSceneFile) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("drumlab-file-fill-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "packings");
  std::ofstream(dir / "packings" / "p.csv")
      << "x,y,z,r\n0,-0.02,0.01,0.004\n0.02,-0.02,0.01,0.008\n";
  std::ofstream(dir / "s.toml") << scene_text("kind = \"file\"\nfile = \"packings/p.csv\"");
  const SceneConfig scene = load_scene(dir / "s.toml");
  EXPECT_EQ(scene.fill.kind, FillKind::file);
  EXPECT_TRUE(scene.dynamic());
  const Particles p = initial_fill(scene);
  EXPECT_EQ(p.size(), 2u);
  std::ofstream(dir / "bad.toml") << scene_text("kind = \"file\"\nfile = \"none.csv\"");
  try {
    load_scene(dir / "bad.toml");
    ADD_FAILURE() << "missing file accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fill.file"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace drumlab
