// Checkpoints: every array of the state survives the HDF5 round trip bit for bit, and a run
// continued from a checkpoint after N steps is bit-identical to an uninterrupted run of 2N steps
// (friction and rolling on particles and walls, drum turning, so the contact and wall history
// matter: the test also shows that dropping them changes the trajectory). Bad paths and files give
// InputError and leave nothing under the final name.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "engine/io/checkpoint.hpp"
#include "tests/same_bits.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/file_size_limit.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

constexpr std::uint64_t kN = 300;

void expect_same_state(const SimulationState& a, const SimulationState& b) {
  EXPECT_TRUE(same_bits(a.particles.position, b.particles.position));
  EXPECT_TRUE(same_bits(a.particles.velocity, b.particles.velocity));
  EXPECT_TRUE(same_bits(a.particles.omega, b.particles.omega));
  EXPECT_TRUE(same_bits(a.particles.force, b.particles.force));
  EXPECT_TRUE(same_bits(a.particles.torque, b.particles.torque));
  EXPECT_TRUE(same_bits(a.particles.radius, b.particles.radius));
  EXPECT_TRUE(same_bits(a.particles.mass, b.particles.mass));
  EXPECT_TRUE(same_bits(a.particles.inv_mass, b.particles.inv_mass));
  EXPECT_TRUE(same_bits(a.particles.inv_inertia, b.particles.inv_inertia));
  EXPECT_EQ(a.particles.size_class, b.particles.size_class);
  EXPECT_EQ(a.particles.id, b.particles.id);
  EXPECT_TRUE(same_bits(a.time, b.time));
  EXPECT_TRUE(same_bits(a.dt, b.dt));
  EXPECT_TRUE(same_bits(a.drum_angle, b.drum_angle));
  EXPECT_TRUE(same_bits(a.drum_omega, b.drum_omega));
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.search_method, b.search_method);
  EXPECT_EQ(a.contact_row_start, b.contact_row_start);
  EXPECT_EQ(a.contact_col, b.contact_col);
  EXPECT_TRUE(same_bits(a.contact_history, b.contact_history));
  ASSERT_EQ(a.wall_history.size(), b.wall_history.size());
  EXPECT_EQ(std::memcmp(a.wall_history.data(), b.wall_history.data(),
                        a.wall_history.size() * sizeof(a.wall_history[0])),
            0);
}

std::size_t nonzero(const std::vector<Vec3>& v) {
  std::size_t n = 0;
  for (const Vec3& x : v) n += x.squaredNorm() > 0.0;
  return n;
}

TEST(Checkpoint, RoundTripKeepsEveryBit) {
  TempDir dir("checkpoint-roundtrip");
  const SceneConfig scene = output_scene();
  const auto sim = settled_simulation(scene, kN);
  const SimulationState s = sim->state();
  ASSERT_GT(s.contact_col.size(), 10u);
  ASSERT_GT(nonzero(s.contact_history), 5u) << "needs live tangential history";
  std::size_t wall_live = 0;
  for (const auto& w : s.wall_history) wall_live += w[0].squaredNorm() > 0.0;
  ASSERT_GT(wall_live, 5u) << "needs live wall history";

  const auto file = dir.path() / "state.h5";
  write_checkpoint(file, s, scene.name);
  const Checkpoint c = read_checkpoint(file);
  EXPECT_EQ(c.scene_name, scene.name);
  expect_same_state(s, c.state);
  // No temporary left beside it.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

// An MPI rank reads its share of a checkpoint (read_checkpoint_rows): three pieces of rows hold,
// together and in order, every array of the whole file, its wall history and its contact rows
// (row starts from 0 in each piece, partners as slots of the whole file), bit for bit.
TEST(Checkpoint, RowsReadInPiecesAreTheWholeCheckpoint) {
  TempDir dir("checkpoint-rows");
  const SceneConfig scene = output_scene();
  const auto sim = settled_simulation(scene, kN);
  const std::filesystem::path file = dir.path() / "state.h5";
  write_checkpoint(file, sim->state(), scene.name);
  const Checkpoint whole = read_checkpoint(file);
  const SimulationState& w = whole.state;
  const std::size_t n = whole.particles;
  ASSERT_EQ(n, w.particles.size());
  ASSERT_GT(n, 100u);
  ASSERT_GT(w.contact_col.size(), 10u);
  SimulationState joined = w;
  joined.particles = Particles{};
  joined.wall_history.clear();
  joined.contact_row_start = {0};
  joined.contact_col.clear();
  joined.contact_history.clear();
  const std::size_t a = n / 3, b = 2 * n / 3 + 7;
  for (const auto& [first, count] :
       {std::pair<std::size_t, std::size_t>{0, a}, {a, b - a}, {b, n - b}}) {
    const Checkpoint piece = read_checkpoint_rows(file, first, count);
    const SimulationState& p = piece.state;
    EXPECT_EQ(piece.particles, n);
    ASSERT_EQ(p.particles.size(), count);
    ASSERT_EQ(p.contact_row_start.size(), count + 1);
    EXPECT_EQ(p.contact_row_start.front(), 0u);
    EXPECT_EQ(p.time, w.time);
    EXPECT_EQ(p.steps, w.steps);
    for (std::size_t i = 0; i < count; ++i) {
      joined.particles.add(p.particles.position[i], p.particles.radius[i], 1.0,
                           p.particles.size_class[i]);
      const std::size_t k = joined.particles.size() - 1;
      joined.particles.velocity[k] = p.particles.velocity[i];
      joined.particles.omega[k] = p.particles.omega[i];
      joined.particles.force[k] = p.particles.force[i];
      joined.particles.torque[k] = p.particles.torque[i];
      joined.particles.mass[k] = p.particles.mass[i];
      joined.particles.inv_mass[k] = p.particles.inv_mass[i];
      joined.particles.inv_inertia[k] = p.particles.inv_inertia[i];
      joined.particles.id[k] = p.particles.id[i];
      joined.wall_history.push_back(p.wall_history[i]);
      joined.contact_row_start.push_back(joined.contact_col.size() + p.contact_row_start[i + 1] -
                                         p.contact_row_start[i]);
      for (std::size_t e = p.contact_row_start[i]; e < p.contact_row_start[i + 1]; ++e) {
        joined.contact_col.push_back(p.contact_col[e]);
        joined.contact_history.push_back(p.contact_history[e]);
      }
    }
  }
  expect_same_state(w, joined);
  EXPECT_THROW(read_checkpoint_rows(file, n - 50, 100), InputError);
  // A state whose contact list was never built (no row starts) reads in rows without contacts.
  SimulationState bare = w;
  bare.contact_row_start.clear();
  bare.contact_col.clear();
  bare.contact_history.clear();
  write_checkpoint(dir.path() / "bare.h5", bare, scene.name);
  const Checkpoint piece = read_checkpoint_rows(dir.path() / "bare.h5", 10, 20);
  EXPECT_EQ(piece.state.particles.size(), 20u);
  EXPECT_TRUE(piece.state.contact_row_start.empty());
  EXPECT_TRUE(piece.state.contact_col.empty());
}

TEST(Checkpoint, RestartAfterNStepsIsBitIdenticalToTwoN) {
  TempDir dir("checkpoint-restart");
  const SceneConfig scene = output_scene();
  const auto straight = settled_simulation(scene, 2 * kN);

  const auto first = settled_simulation(scene, kN);
  write_checkpoint(dir.path() / "half.h5", first->state(), scene.name);
  Simulation continued(scene, read_checkpoint(dir.path() / "half.h5").state);
  continued.advance(kN);
  EXPECT_EQ(continued.steps(), 2 * kN);
  expect_same_state(straight->state(), continued.state());

  // The history is what makes this hard: a restart without it goes elsewhere.
  SimulationState forgetful = first->state();
  for (Vec3& h : forgetful.contact_history) h.setZero();
  for (auto& w : forgetful.wall_history) w.fill(Vec3::Zero());
  Simulation amnesiac(scene, std::move(forgetful));
  amnesiac.advance(kN);
  EXPECT_FALSE(same_bits(straight->particles().position, amnesiac.particles().position));
  EXPECT_FALSE(same_bits(straight->particles().omega, amnesiac.particles().omega));
}

// A start may hold the wall overlap a run may reach (time.max_overlap): a state saved under a
// raised limit restarts under it, and a start deeper in the wall than the limit is refused.
TEST(Checkpoint, StartTakesTheWallOverlapTheRunMayReach) {
  SceneConfig scene = output_scene();
  SimulationState state = settled_simulation(scene, 10)->state();
  Particles& p = state.particles;
  // Particle 0 pressed into the mantle by 0.7 of its radius.
  const double r = p.radius[0];
  const Vec3 x = p.position[0];
  const double rho = std::hypot(x.x(), x.y());
  const double to = 0.5 * scene.drum.diameter - r + 0.7 * r;
  p.position[0] = Vec3(x.x() * to / rho, x.y() * to / rho, x.z());
  try {
    Simulation refused(scene, state);
    ADD_FAILURE() << "a start 0.7 radii into the wall under time.max_overlap = 0.5";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("time.max_overlap = 0.5"), std::string::npos) << e.what();
  }
  scene.time.max_overlap = 1.0;
  EXPECT_NO_THROW(Simulation(scene, state));
}

TEST(Checkpoint, RestartIsBitIdenticalWithPeriodicEndsTiltAndSwitchedSearch) {
  TempDir dir("checkpoint-periodic");
  std::string text = output_scene_text();
  text.replace(text.find("omega = 3.0"), 11, "omega = 3.0\nends = \"periodic\"\ntilt_deg = 10");
  const SceneConfig scene = parse_scene(text, "periodic-test");
  ASSERT_EQ(scene.drum.ends, DrumEnds::periodic);
  auto straight = settled_simulation(scene, kN);
  straight->set_search_method("m2");
  straight->advance(kN);

  auto first = settled_simulation(scene, kN);
  first->set_search_method("m2");
  write_checkpoint(dir.path() / "half.h5", first->state(), scene.name);
  Simulation continued(scene, read_checkpoint(dir.path() / "half.h5").state);
  EXPECT_EQ(continued.search().name(), "m2");
  continued.advance(kN);
  expect_same_state(straight->state(), continued.state());
}

TEST(Checkpoint, RestartKeepsASwitchedSearchMethod) {
  const SceneConfig scene = output_scene();
  auto sim = settled_simulation(scene, 50);
  sim->set_search_method("m1");
  Simulation restored(scene, sim->state());
  EXPECT_EQ(restored.search().name(), "m1");
}

TEST(Checkpoint, BadPathsAndFilesGiveInputErrors) {
  TempDir dir("checkpoint-bad");
  const SceneConfig scene = output_scene();
  const auto sim = settled_simulation(scene, 10);
  const auto missing_dir = dir.path() / "no-such-dir" / "c.h5";
  EXPECT_THROW(write_checkpoint(missing_dir, sim->state(), scene.name), InputError);
  EXPECT_FALSE(std::filesystem::exists(missing_dir));
  // A directory in the way of the final name: the rename fails, the temporary is removed.
  std::filesystem::create_directories(dir.path() / "taken.h5" / "x");
  EXPECT_THROW(write_checkpoint(dir.path() / "taken.h5", sim->state(), scene.name), InputError);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);

  EXPECT_THROW(read_checkpoint(dir.path() / "none.h5"), InputError);
  const auto text = dir.write("text.h5", "not hdf5\n");
  EXPECT_THROW(read_checkpoint(text), InputError);

  // Inconsistent state: the contact list does not fit the particles.
  SimulationState broken = sim->state();
  broken.contact_row_start.pop_back();
  EXPECT_THROW(Simulation(scene, std::move(broken)), InputError);
  SimulationState unsorted = sim->state();
  unsorted.wall_history.pop_back();
  EXPECT_THROW(Simulation(scene, std::move(unsorted)), InputError);
}

TEST(Checkpoint, FullDiskLeavesNoFileUnderTheFinalName) {
  TempDir dir("checkpoint-full-disk");
  const SceneConfig scene = output_scene();
  const auto sim = settled_simulation(scene, 10);
  const SimulationState s = sim->state();
  const auto file = dir.path() / "c.h5";
  {
    const FileSizeLimit limit(8 * 1024);  // the state needs about 60 kB
    ASSERT_TRUE(limit.ok());
    EXPECT_THROW(write_checkpoint(file, s, scene.name), InputError);
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 0);
  write_checkpoint(file, s, scene.name);  // and with room it works
  EXPECT_TRUE(std::filesystem::exists(file));
}

}  // namespace
}  // namespace drumlab::test
