// Triangle walls in the step ([[wall.mesh]], [[wall.lifters]]; engine/mesh/, engine/contact/
// mesh_wall_loop.cpp): a sphere pressed onto, sliding and rolling across a flat square of 2, 8
// and 200 triangles feels the analytic plane's force and torque at every step (the drum's end cap
// with the same law), edge and vertex crossings included; a lifter drum restarts bit for bit and
// gives the same bits for every thread count and search method; the keys and their one-line
// errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "engine/contact/contact_model.hpp"
#include "engine/contact/mesh_wall_history.hpp"
#include "engine/fill/random_fill.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/mesh/lifters.hpp"
#include "engine/mesh/mesh_wall_set.hpp"
#include "engine/mesh/stl_file.hpp"
#include "engine/scene/scene_writer.hpp"
#include "engine/simulation.hpp"
#include "engine/threads.hpp"
#include "tests/same_bits.hpp"
#include "tests/small_drum_text.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/mesh_test_shapes.hpp"

namespace drumlab::test {
namespace {

/// One sphere's prescribed motion at a step.
struct Pose {
  Vec3 x, v, w;
};

/// The motions of the flat-square test on a square of half side `half`, for a sphere of radius
/// r: pressed in at the centre (a vertex of even grids), sliding along y = 0 (an inner edge of
/// even grids), rolling along the diagonal (through the grid's vertices, along the triangles'
/// diagonals) and sliding with spin across the cells off every grid line.
std::vector<Pose> square_poses(double r, double half) {
  std::vector<Pose> out;
  const double depth = 0.02 * r, speed = 0.2;
  for (int k = 0; k < 60; ++k) {  // pressed in, then held
    const double d = depth * std::min(1.0, (k + 1) / 40.0);
    out.push_back({Vec3(0.0, 0.0, r - d), Vec3(0.0, 0.0, -0.01), Vec3::Zero()});
  }
  const auto path = [&](const Vec3& a, const Vec3& b, int steps, bool rolls, const Vec3& spin) {
    const Vec3 v = speed * (b - a).normalized();
    for (int k = 0; k <= steps; ++k) {
      const Vec3 x = a + (b - a) * (static_cast<double>(k) / steps);
      const Vec3 w = rolls ? Vec3(Vec3::UnitZ().cross(v) / r) : spin;
      out.push_back({Vec3(x.x(), x.y(), r - depth), v, w});
    }
  };
  const double e = 0.7 * half;
  path(Vec3(-e, 0.0, 0.0), Vec3(e, 0.0, 0.0), 400, false, Vec3::Zero());
  path(Vec3(-e, -e, 0.0), Vec3(e, e, 0.0), 400, true, Vec3::Zero());
  path(Vec3(-e, 0.123 * half, 0.0), Vec3(e, -0.377 * half, 0.0), 400, false, Vec3(3.0, -2.0, 5.0));
  return out;
}

/// `cohesion`: with dry adhesion (sjkr), which pulls onto a mesh as onto the plane.
SceneConfig flat_scene(bool cohesion) {
  SmallDrumText t;
  t.omega = "0.0";
  t.rolling_friction = "0.05";
  t.wall = "friction = 0.4\nrolling_friction = 0.05";
  const std::string adhesion = cohesion ? "[cohesion]\nenergy_density = 3e4\n" : "";
  SceneConfig s = parse_scene(t.text() + adhesion, "flat.toml");
  // The mesh's law: the wall's material (the model builds it from the mesh's keys).
  MeshWallConfig m;
  m.material = {s.wall.youngs_modulus, s.wall.poisson_ratio, s.wall.restitution, s.wall.friction,
                s.wall.rolling_friction};
  s.meshes.push_back(m);
  return s;
}

Particles one_sphere(const ContactModel& model, double r) {
  Particles p;
  p.add(Vec3(0.0, 0.0, r), r, 2500.0, 0);
  for (const std::string_view name : model.particle_arrays(kWallParts)) p.add_array(name, 0.0);
  return p;
}

TEST(MeshWalls, AFlatSquareOfAnyTrianglesPushesAndTurnsASphereAsThePlaneDoes) {
  for (const bool cohesion : {false, true}) {
    const SceneConfig scene = flat_scene(cohesion);
    const ContactModel model(scene);
    const Drum drum(scene.drum);
    const double r = 0.008, half = 0.04, dt = 2e-6;
    const std::vector<Pose> poses = square_poses(r, half);
    for (const int cells : {1, 2, 10}) {
      WallMesh wall{make_mesh(grid_square(cells, Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), half),
                              0.01, "square"),
                    MeshAttach::lab, scene.meshes[0].material, "wall.mesh[0]"};
      ASSERT_EQ(wall.mesh.patches, 1u);
      const std::size_t triangles = wall.mesh.size();
      const MeshWallSet walls({wall}, 2.0 * r, r);
      Particles plane = one_sphere(model, r), mesh = one_sphere(model, r);
      WallHistory history(1, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
      const std::vector<Index> candidate = {0};
      double worst_force = 0.0, worst_torque = 0.0, largest_torque = 0.0;
      for (std::size_t k = 0; k < poses.size(); ++k) {
        for (Particles* p : {&plane, &mesh}) {
          p->position[0] = poses[k].x;
          p->velocity[0] = poses[k].v;
          p->omega[0] = poses[k].w;
          p->clear_forces();
        }
        const double h = k == 0 ? 0.0 : dt;
        model.add_wall_forces(plane, candidate, drum, 0.0, history, dt, h);
        ASSERT_EQ(model.add_mesh_forces(mesh, walls, 0.0, 0.0, dt, h), 1u) << "step " << k;
        const Vec3& f = plane.force[0];
        const Vec3& t = plane.torque[0];
        ASSERT_GT(f.norm(), 0.0);
        worst_force = std::max(worst_force, (mesh.force[0] - f).norm() / f.norm());
        worst_torque = std::max(worst_torque, (mesh.torque[0] - t).norm() / (f.norm() * r));
        largest_torque = std::max(largest_torque, t.norm() / (f.norm() * r));
      }
      std::printf(
          "flat square of %zu triangles%s, %zu steps: worst |dF|/|F| = %.2e, worst "
          "|dT|/(|F| r) = %.2e (torques up to %.2f |F| r)\n",
          triangles, cohesion ? " with sjkr adhesion" : "", poses.size(), worst_force, worst_torque,
          largest_torque);
      EXPECT_LT(worst_force, 1e-12) << triangles << " triangles";
      EXPECT_LT(worst_torque, 1e-12) << triangles << " triangles";
      EXPECT_GT(largest_torque, 0.1);  // the paths did slide and roll
    }
  }
}

/// The small drum with four straight lifters, 300 particles.
SceneConfig lifter_scene(const std::string& search = "m5") {
  SmallDrumText t;
  t.search = search;
  t.omega = "3.0";
  t.wall = "friction = 0.5\n[[wall.lifters]]\ncount = 4\nheight = 0.02";
  return parse_scene(t.text(), "lifters.toml");
}

/// Mesh contacts of the simulation's particles now.
std::size_t mesh_contacts(const Simulation& sim) {
  MeshWallSet::Scratch scratch;
  std::vector<MeshContact> hits;
  std::size_t n = 0;
  const double a = sim.drum_angle();
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {
    sim.meshes().contacts(sim.particles().position[i], sim.particles().radius[i], std::cos(a),
                          std::sin(a), scratch, hits);
    n += hits.size();
  }
  return n;
}

TEST(MeshWalls, ALifterDrumRestartsBitForBitFromItsCheckpoint) {
  const SceneConfig scene = lifter_scene();
  Simulation whole(scene, random_fill(scene));
  whole.advance(1500);
  ASSERT_GT(mesh_contacts(whole), 5u);
  TempDir dir("mesh-restart");
  const auto file = dir.path() / "lifters.h5";
  write_checkpoint(file, whole.state(), scene.name);
  Simulation restarted(scene, read_checkpoint(file).state);
  whole.advance(800);
  restarted.advance(800);
  EXPECT_TRUE(same_bits(whole.particles().position, restarted.particles().position));
  EXPECT_TRUE(same_bits(whole.particles().omega, restarted.particles().omega));
  for (std::size_t k = 0; k < kMeshSlots; ++k) {
    EXPECT_TRUE(same_bits(*whole.particles().find_array(kMeshSpringArrays[k][0]),
                          *restarted.particles().find_array(kMeshSpringArrays[k][0])));
  }
  // Without the mesh history the continuation differs: the history is carried, not rebuilt.
  SimulationState amnesiac = whole.state();
  for (ParticleArray& a : amnesiac.particles.extra)
    std::fill(a.values.begin(), a.values.end(), 0.0);
  Simulation forgetful(scene, amnesiac);
  Simulation remembering(scene, whole.state());
  forgetful.advance(300);
  remembering.advance(300);
  EXPECT_FALSE(same_bits(forgetful.particles().position, remembering.particles().position));
  // A checkpoint of other meshes (more patches than these) does not restart this scene.
  SimulationState other = whole.state();
  other.particles.find_array(kMeshPatchArrays[0])->front() = 1e6;
  try {
    Simulation wrong(scene, other);
    ADD_FAILURE() << "restarted from another mesh's history";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("patches"), std::string::npos) << e.what();
  }
}

TEST(MeshWalls, ALifterDrumGivesTheSameBitsForAnyThreadCountAndMethod) {
  const Particles start = random_fill(lifter_scene());
  const int saved = max_threads();
  std::vector<Vec3> position;
  for (const auto& [threads, method] :
       {std::pair{1, "m5"}, {2, "m5"}, {3, "verlet:m2"}, {2, "brute"}, {1, "m1"}}) {
    set_thread_count(threads);
    Simulation sim(lifter_scene(method), start);
    sim.advance(1200);
    ASSERT_GT(mesh_contacts(sim), 5u);
    if (position.empty()) {
      position = sim.particles().position;
      continue;
    }
    EXPECT_TRUE(same_bits(position, sim.particles().position)) << threads << " " << method;
  }
  set_thread_count(saved);
}

TEST(MeshWalls, KeysRoundTripAndBadOnesAreOneLineNamingTheKeyAndFile) {
  TempDir dir("mesh-keys");
  // A closed box as an STL file, and damaged copies of it.
  TriangleMesh box = make_mesh(
      box_triangles(Vec3(0.0, -0.05, 0.025), Vec3::UnitX(), Vec3::UnitY(), Vec3(0.01, 0.01, 0.01)),
      0.3, "box");
  write_stl(box, dir.path() / "box.stl");
  {
    std::ofstream open_box(dir.path() / "open.stl");
    open_box << "solid open\nfacet normal 0 0 1\nouter loop\nvertex 0 -0.05 0.02\n"
                "vertex 0.01 -0.05 0.02\nvertex 0 -0.04 0.02\nendloop\nendfacet\nendsolid open\n";
    std::ofstream nan_box(dir.path() / "nan.stl");
    nan_box << "solid n\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\nvertex 0.01 0 0\n"
               "vertex 0 0.01 0\nendloop\nendfacet\nendsolid n\n";
    std::ofstream flat(dir.path() / "flat.stl");
    flat << "solid f\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0.01\nvertex 0.01 0 0.01\n"
            "vertex 0.02 0 0.01\nendloop\nendfacet\nendsolid f\n";
  }
  std::filesystem::copy_file(dir.path() / "box.stl", dir.path() / "cut.stl");
  std::filesystem::resize_file(dir.path() / "cut.stl", 400);
  const auto scene_with = [&](const std::string& wall) {
    SmallDrumText t;
    t.wall = wall;
    return t.text();
  };
  const std::string scene_file = (dir.path() / "s.toml").string();
  const SceneConfig s = parse_scene(
      scene_with("[[wall.mesh]]\nfile = \"box.stl\"\nattach = \"lab\"\nfriction = 0.2\n"
                 "closed = true\n[[wall.lifters]]\ncount = 3\nheight = 0.015\nshape = \"angled\""),
      scene_file);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].file, dir.path() / "box.stl");
  EXPECT_EQ(s.meshes[0].attach, MeshAttach::lab);
  EXPECT_EQ(s.meshes[0].material.friction, 0.2);
  EXPECT_EQ(s.meshes[0].material.restitution, s.wall.restitution);
  ASSERT_EQ(s.lifters.size(), 1u);
  EXPECT_EQ(s.lifters[0].shape, LifterKind::angled);
  EXPECT_EQ(parse_scene(scene_to_toml(s, dir.path()), scene_file), s);  // written and read back

  const struct {
    std::string wall, expected;
  } bad[] = {
      {"[[wall.mesh]]\nfile = \"missing.stl\"", "wall.mesh[0]: "},
      {"[[wall.mesh]]\nfile = \"cut.stl\"", "cut.stl: a binary STL of 12 triangles needs 684"},
      {"[[wall.mesh]]\nfile = \"nan.stl\"", "nan.stl"},
      {"[[wall.mesh]]\nfile = \"flat.stl\"", "degenerate"},
      {"[[wall.mesh]]\nfile = \"open.stl\"\nclosed = true", "not a closed surface"},
      {"[[wall.mesh]]\nfile = \"box.stl\"\noffset = [1.0, 0.0, 0.0]", "lies outside the drum"},
      {"[[wall.mesh]]\nfile = \"box.stl\"\nscale = -1.0", "wall.mesh[0].scale: must be"},
      {"[[wall.mesh]]\nfile = \"box.stl\"\nattach = \"floor\"", "wall.mesh[0].attach: unknown"},
      {"[[wall.lifters]]\ncount = 4\nheight = 0.2", "wall.lifters[0].height: must be in (0, R"},
      {"[[wall.lifters]]\nheight = 0.02\nangle_deg = 30.0", "only with shape = \"angled\""},
      {"[[wall.lifters]]\nheight = 0.02\nfriction = -1.0", "wall.lifters[0].friction"},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(b.expected);
    try {
      parse_scene(scene_with(b.wall), scene_file);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(b.expected), std::string::npos) << what;
      EXPECT_EQ(what.rfind(scene_file, 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  // The command line: exit 2, one line, nothing written.
  {
    std::ofstream out(scene_file);
    out << scene_with("[[wall.mesh]]\nfile = \"cut.stl\"") << "[output]\ndirectory = \""
        << (dir.path() / "out").string() << "\"\n";
  }
  const CliResult run = run_cli("run " + scene_file + " --vtu " + (dir.path() / "vtu").string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("cut.stl"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "vtu"));
}

}  // namespace
}  // namespace drumlab::test
