// drumlab-mpi against drumlab run: the same scene on 1-4 ranks gives the serial run's state bit for
// bit (positions, velocities, angular velocities, forces, ids, the contact set with its tangential
// history, the wall history), with caps, periodic ends and a tilted drum, through re-orderings,
// migrations and RCB re-balances; and checkpoints restart across rank counts (N -> M, N -> serial,
// serial -> N) as the uninterrupted run. Compared through the checkpoints both write (the serial
// layout, engine/io/checkpoint.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "engine/io/h5_file.hpp"
#include "engine/io/h5_series.hpp"
#include "engine/periodic.hpp"
#include "tests/mpi/mpi_runner.hpp"
#include "tests/same_bits.hpp"
#include "tests/small_drum_text.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

/// 700 particles (three of the pair loop's blocks of 256 rows, pair_block_rows), settling 0.004 s
/// (41 steps), re-ordered every 30 steps, a small Verlet skin so that particles migrate often.
/// (Short: ranks oversubscribed on a busy 2-core machine take tens of milliseconds a step, each one
/// waiting for the others to be scheduled.)
std::string scene_text(const std::string& search, const std::string& drum_extra,
                       const std::string& ends) {
  SmallDrumText t;
  t.search = search;
  t.omega = "6.0" + drum_extra;
  t.ends = ends;
  t.time = "dt_factor = 0.2\nduration = 0.01";
  t.output = "diagnostics_every = 50";
  t.depth = "0.1";
  t.fill = "count = 700\nsettle_time = 0.004\nseed = 3";
  t.gravity = "[0.0, -150.0, 0.0]";  // packs the loose fill into a bed within these few steps
  return t.text() + "[performance]\nsort_every = 30\nverlet_skin = 0.1\npair_block_rows = 256\n";
}

/// The contacts of a state: the listed pairs that overlap, as (id, id) with their tangential
/// history. (A Verlet list also lists pairs apart within its skin, with zero history; which of
/// those it holds depends on when it was last rebuilt, which a decomposed run does more often.)
struct Contact {
  Index a, b;
  Vec3 history;
};
std::vector<Contact> contacts(const SimulationState& s, double period) {
  std::vector<Contact> out;
  const Particles& p = s.particles;
  for (std::size_t i = 0; i + 1 < s.contact_row_start.size(); ++i) {
    for (std::size_t k = s.contact_row_start[i]; k < s.contact_row_start[i + 1]; ++k) {
      const Index j = s.contact_col[k];
      const double r = p.radius[i] + p.radius[j];
      if (nearest_image(p.position[i], p.position[j], period).squaredNorm() >= r * r) continue;
      out.push_back({p.id[i], p.id[j], s.contact_history[k]});
    }
  }
  return out;
}

/// Equal bit for bit: every particle array, the contacts and their history, the wall history,
/// the clock.
void expect_same_state(const SimulationState& a, const SimulationState& b, const std::string& what,
                       double period = 0.0) {
  SCOPED_TRACE(what);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  EXPECT_EQ(a.particles.id, b.particles.id);  // ids conserved, in the serial order
  EXPECT_TRUE(same_bits(a.particles.position, b.particles.position));
  EXPECT_TRUE(same_bits(a.particles.velocity, b.particles.velocity));
  EXPECT_TRUE(same_bits(a.particles.omega, b.particles.omega));
  EXPECT_TRUE(same_bits(a.particles.force, b.particles.force));
  EXPECT_TRUE(same_bits(a.particles.torque, b.particles.torque));
  const auto ca = contacts(a, period), cb = contacts(b, period);
  EXPECT_GT(ca.size(), 200u);  // a bed in contact, not a gas (~230 after 60 steps, ~450 after 120)
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t k = 0; k < ca.size(); ++k) {
    EXPECT_TRUE(ca[k].a == cb[k].a && ca[k].b == cb[k].b) << "contact " << k;
    EXPECT_TRUE(same_bits(std::vector{ca[k].history}, std::vector{cb[k].history})) << k;
  }
  ASSERT_EQ(a.wall_history.size(), b.wall_history.size());
  EXPECT_TRUE(same_bits(a.wall_history, b.wall_history));
  ASSERT_EQ(a.particles.extra.size(), b.particles.extra.size());
  for (std::size_t k = 0; k < a.particles.extra.size(); ++k) {
    EXPECT_EQ(a.particles.extra[k].name, b.particles.extra[k].name);
    EXPECT_TRUE(same_bits(a.particles.extra[k].values, b.particles.extra[k].values))
        << a.particles.extra[k].name;
  }
  EXPECT_TRUE(same_bits(a.time, b.time));
  EXPECT_TRUE(same_bits(a.carrier_angle, b.carrier_angle));
  EXPECT_EQ(a.steps, b.steps);
}

class MpiRun : public MpiCase {
 protected:
  /// Balance checks every 50 steps, each re-cutting (3 re-balances in the 161 steps): by
  /// `balance` "count", or by "time" with threshold 0 (cuts that depend on the measured times, so
  /// they differ from run to run: the state must not).
  void same_on_ranks(const std::string& text, std::initializer_list<int> ranks, double period,
                     const std::string& balance) {
    const std::string scene = dir.write("scene.toml", text);
    const std::string args =
        "--steps 120 --rebalance-every 50 --balance-threshold 0 --balance " + balance;
    const SimulationState want = serial(scene, "--steps 120", "serial.h5");
    for (const int r : ranks) {
      expect_same_state(want, parallel(r, scene, args, "mpi.h5"), std::to_string(r) + " ranks",
                        period);
      if (r > 1) {
        EXPECT_NE(last_output.find(", 3 re-balances"), std::string::npos) << last_output;
      }
    }
  }
};

TEST_F(MpiRun, CapsDrumIsBitIdenticalOnOneToFourRanks) {
  same_on_ranks(scene_text("verlet:m2", "", ""), {1, 2, 3, 4}, 0.0, "count");
}

TEST_F(MpiRun, HybridTwoRanksTimesTwoThreadsIsBitIdentical) {
  const std::string scene = dir.write("scene.toml", scene_text("m5", "", ""));
  const SimulationState want = serial(scene, "--steps 60", "serial.h5");
  expect_same_state(want, parallel(2, scene, "--steps 60", "mpi.h5", 2), "2 ranks x 2 threads");
}

TEST_F(MpiRun, PeriodicDrumIsBitIdenticalOnTwoAndThreeRanks) {
  same_on_ranks(scene_text("m5", "", "periodic"), {2, 3}, 0.1, "time");
}

TEST_F(MpiRun, TiltedDrumIsBitIdenticalOnTwoAndFourRanks) {
  same_on_ranks(scene_text("verlet:m2", "\ntilt_deg = 20.0", ""), {2, 4}, 0.0, "time");
}

// A planetary carrier ([drum.orbit], 5.4 g turning with the arm) on the ranks gives the serial
// bits.
TEST_F(MpiRun, PlanetaryDrumIsBitIdenticalOnTwoRanks) {
  same_on_ranks(scene_text("verlet:m2", "\n[drum.orbit]\nradius = 0.3\nomega = 13.0", ""), {2}, 0.0,
                "count");
}

// Lifters ([[wall.lifters]], triangle walls turning with the drum) on the ranks: the serial
// bits, the mesh history (per-particle arrays) included, through migrations and re-balances.
TEST_F(MpiRun, LifterDrumIsBitIdenticalOnTwoAndThreeRanks) {
  same_on_ranks(scene_text("verlet:m2", "", "") + "[[wall.lifters]]\ncount = 4\nheight = 0.02\n",
                {2, 3}, 0.0, "count");
  const SimulationState s = read_checkpoint(dir.file("serial.h5")).state;
  const std::vector<double>* slot = s.particles.find_array("mesh_patch_0");
  ASSERT_NE(slot, nullptr);
  EXPECT_GT(std::count_if(slot->begin(), slot->end(), [](double v) { return v != 0.0; }), 10);
}

TEST_F(MpiRun, CheckpointsRestartAcrossRankCounts) {
  const std::string scene = dir.write("scene.toml", scene_text("verlet:m2", "", ""));
  const SimulationState whole = serial(scene, "--steps 120", "whole.h5");
  // N -> M and N -> serial
  parallel(3, scene, "--steps 60", "half3.h5");
  expect_same_state(whole,
                    parallel(2, scene, "--steps 60 --restart " + dir.file("half3.h5"), "a.h5"),
                    "3 -> 2 ranks");
  expect_same_state(whole, serial(scene, "--steps 60 --restart " + dir.file("half3.h5"), "b.h5"),
                    "3 ranks -> serial");
  // serial -> N
  serial(scene, "--steps 60", "half1.h5");
  expect_same_state(whole,
                    parallel(4, scene, "--steps 60 --restart " + dir.file("half1.h5"), "c.h5"),
                    "serial -> 4 ranks");
}

// The series drumlab-mpi gathers on rank 0 is the serial run's series: the same frames (frame 0
// at the start of the turn, then every --every steps), times, steps, ids and positions bit for
// bit; and `drumlab convert` reads it. An unwritable series path stops every rank with one line.
TEST_F(MpiRun, SeriesIsTheSerialRunsSeriesFrameByFrame) {
  const std::string scene = dir.write("scene.toml", scene_text("verlet:m2", "", ""));
  serial(scene, "--steps 80 --every 40 --h5 " + dir.file("serial_series.h5"), "s.h5");
  parallel(3, scene, "--steps 80 --every 40 --h5 " + dir.file("mpi_series.h5"), "m.h5");
  const SeriesInfo want = read_series_info(dir.file("serial_series.h5"));
  const SeriesInfo got = read_series_info(dir.file("mpi_series.h5"));
  ASSERT_EQ(want.frames, 3u);
  ASSERT_EQ(got.frames, want.frames);
  EXPECT_TRUE(got.complete);
  for (std::size_t k = 0; k < want.frames; ++k) {
    const SeriesFrame a = read_series_frame(dir.file("serial_series.h5"), k);
    const SeriesFrame b = read_series_frame(dir.file("mpi_series.h5"), k);
    EXPECT_EQ(a.time, b.time) << "frame " << k;
    EXPECT_EQ(a.step, b.step) << "frame " << k;
    ASSERT_EQ(a.id, b.id) << "frame " << k;
    EXPECT_TRUE(same_bits(a.position, b.position)) << "frame " << k;
    EXPECT_TRUE(same_bits(a.velocity, b.velocity)) << "frame " << k;
    EXPECT_TRUE(same_bits(a.omega, b.omega)) << "frame " << k;
  }
  // The sidecar rank 0 writes is the serial run's, but for the file name it refers to.
  std::string xdmf = read_text(dir.file("mpi_series.xdmf"));
  for (std::size_t at; (at = xdmf.find("mpi_series.h5")) != std::string::npos;) {
    xdmf.replace(at, 13, "serial_series.h5");
  }
  EXPECT_EQ(xdmf, read_text(dir.file("serial_series.xdmf")));
  const Ran convert = shell(std::string(DRUMLAB_CLI) + " convert " + dir.file("mpi_series.h5") +
                            " --vtu " + dir.file("vtu"));
  EXPECT_EQ(convert.exit_code, 0) << convert.output;
  const Ran bad = shell(mpirun(2) + DRUMLAB_MPI_CLI + " run " + scene +
                        " --steps 10 --h5 /nonexistent-dir/s.h5");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("/nonexistent-dir/s.h5"), std::string::npos) << bad.output;
}

TEST_F(MpiRun, KilledRankStopsEveryRankAndLeavesARestartableCheckpoint) {
  const std::string scene = dir.write("scene.toml", scene_text("verlet:m2", "", ""));
  const std::string ck = dir.file("ck.h5");
  // A long run checkpointing every 20 steps; once a checkpoint exists, SIGKILL one rank (a child
  // of this mpirun only) and wait for mpirun to stop the others.
  const std::string script =
      mpirun(2) + DRUMLAB_MPI_CLI + " run " + scene + " --steps 100000000 --checkpoint " + ck +
      " --checkpoint-every 20 > " + dir.file("run.log") + " 2>&1 & M=$!\n" +
      "for i in $(seq 600); do [ -f " + ck +
      " ] && break; sleep 0.1; done\n"
      "sleep 0.5\n"
      "R=$(pgrep -P $M -f drumlab-mpi | head -n 1)\n"
      "[ -n \"$R\" ] && kill -9 $R && echo killed\n"
      "for i in $(seq 600); do kill -0 $M 2>/dev/null || break; sleep 0.1; done\n"
      "if kill -0 $M 2>/dev/null; then echo still running; kill -9 $M; fi\n"
      "wait $M; echo \"mpirun exit $?\"\n";
  const Ran r = shell("bash -c '" + script + "'");
  EXPECT_NE(r.output.find("killed"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("still running"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("mpirun exit 0"), std::string::npos) << r.output;
  const Checkpoint c = read_checkpoint(ck);  // intact: complete, readable
  EXPECT_EQ(c.state.particles.size(), 700u);
  EXPECT_GE(c.state.steps, 60u);  // written after settling (~41 steps) and 20 turning steps
  const Ran again = shell(std::string(DRUMLAB_CLI) + " run " + scene + " --threads 1 --steps 10 " +
                          "--restart " + ck);
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

/// Every dataset and root attribute of two checkpoints, value for value (bits for doubles).
void expect_same_datasets(const std::string& a, const std::string& b) {
  const h5::Handle fa = h5::open_file(a), fb = h5::open_file(b);
  const hid_t x = fa.get(), y = fb.get();
  constexpr std::size_t any = h5::kAnySize;
  for (const char* name :
       {"particles/position", "particles/velocity", "particles/omega", "particles/force",
        "particles/torque", "particles/radius", "particles/mass", "particles/inv_mass",
        "particles/inv_inertia", "contacts/history", "walls/history"}) {
    EXPECT_TRUE(same_bits(h5::read_doubles(x, name, any), h5::read_doubles(y, name, any))) << name;
  }
  EXPECT_EQ(h5::read_u32(x, "particles/id", any), h5::read_u32(y, "particles/id", any));
  EXPECT_EQ(h5::read_u8(x, "particles/size_class", any),
            h5::read_u8(y, "particles/size_class", any));
  EXPECT_EQ(h5::read_u64(x, "contacts/row_start", any), h5::read_u64(y, "contacts/row_start", any));
  EXPECT_EQ(h5::read_u32(x, "contacts/col", any), h5::read_u32(y, "contacts/col", any));
  EXPECT_GT(h5::element_count(x, "contacts/col"), 200u);  // a bed in contact
  for (const char* name : {"time", "dt", "drum_omega", "drum_angle"}) {
    EXPECT_TRUE(same_bits(h5::read_double_attribute(x, name), h5::read_double_attribute(y, name)))
        << name;
  }
  EXPECT_EQ(h5::read_u64_attribute(x, "steps"), h5::read_u64_attribute(y, "steps"));
  for (const char* name : {"format", "scene", "search_method"}) {
    EXPECT_EQ(h5::read_string_attribute(x, name), h5::read_string_attribute(y, name)) << name;
  }
}

// The checkpoint 3 ranks write in parallel into one file (parallel HDF5, each rank its particles'
// rows and their contact records) holds the serial run's checkpoint at the same step, dataset for
// dataset, bit for bit (a cell-grid search: its contact list holds the same pairs however the run
// is cut; a Verlet list's extra pairs depend on when it was rebuilt), and restarts serially as the
// uninterrupted run (CheckpointsRestartAcrossRankCounts restarts one from 3 ranks on 2 and 1);
// --gather-output (gathered on rank 0, the serial writer) writes the same datasets.
TEST_F(MpiRun, ParallelCheckpointHoldsTheSerialRunsDatasets) {
  const std::string scene = dir.write("scene.toml", scene_text("m5", "", ""));
  serial(scene, "--steps 60", "serial.h5");
  parallel(3, scene, "--steps 60", "mpi.h5");
  expect_same_datasets(dir.file("serial.h5"), dir.file("mpi.h5"));
  parallel(2, scene, "--steps 60 --gather-output", "gathered.h5");  // rank 0, serial writer
  expect_same_datasets(dir.file("serial.h5"), dir.file("gathered.h5"));
  const SimulationState whole = serial(scene, "--steps 90", "whole.h5");
  expect_same_state(whole, serial(scene, "--steps 30 --restart " + dir.file("mpi.h5"), "r.h5"),
                    "3 ranks -> serial");
}

// A checkpoint that cannot be read stops every rank with exit 2 and one line naming the file, as a
// bad scene does, and no rank waits forever: read in shares by every rank (a named search method)
// or by rank 0 alone ("auto", which times the candidates on the whole state).
TEST_F(MpiRun, UnreadableCheckpointStopsEveryRankWithOneLine) {
  const std::string scene = dir.write("scene.toml", scene_text("verlet:m2", "", ""));
  const std::string garbage = dir.write("garbage.h5", "not an HDF5 file\n");
  for (const std::string& ck : {dir.file("missing.h5"), garbage}) {
    for (const std::string method : {"", " --method auto"}) {
      const Ran r = shell(mpirun(3) + "--timeout 60 " + DRUMLAB_MPI_CLI + " run " + scene +
                          " --restart " + ck + method);
      EXPECT_EQ(r.exit_code, 2) << r.output;
      const std::size_t first = r.output.find("drumlab-mpi: error: ");
      ASSERT_NE(first, std::string::npos) << r.output;
      EXPECT_EQ(r.output.find("drumlab-mpi: error: ", first + 1), std::string::npos) << r.output;
      EXPECT_NE(r.output.find(ck), std::string::npos) << r.output;
    }
  }
}

// A rank bound to one core (`--bind-to core`) with more threads than the cores it may use gets one
// warning line from rank 0 naming the fix, and runs on; an unbound rank with as many cores as
// threads gets none.
TEST_F(MpiRun, ThreadsSharingABoundRanksCoreAreWarnedAbout) {
  const std::string scene = dir.write("scene.toml", scene_text("m5", "", ""));
  const std::string run = std::string(" ") + DRUMLAB_MPI_CLI + " run " + scene + " --steps 5";
  const Ran bound = shell(mpirun(1) + "--bind-to core" + run + " --threads 3");
  EXPECT_EQ(bound.exit_code, 0) << bound.output;
  const std::size_t at = bound.output.find("drumlab-mpi: warning: a rank may run on ");
  ASSERT_NE(at, std::string::npos) << bound.output;
  EXPECT_EQ(bound.output.find("drumlab-mpi: warning:", at + 1), std::string::npos) << bound.output;
  EXPECT_NE(bound.output.find("--bind-to none"), std::string::npos) << bound.output;
  if (std::thread::hardware_concurrency() >= 2) {
    const Ran free = shell(mpirun(1) + "--bind-to none" + run + " --threads 2");
    EXPECT_EQ(free.exit_code, 0) << free.output;
    EXPECT_EQ(free.output.find("warning"), std::string::npos) << free.output;
  }
}

// A write that fails on one rank only (rank 1, not the one that writes the metadata: a file size
// limit as a full disk, on that process alone; shared memory off, which the limit would break)
// stops every rank with exit 2 and one line naming the file, and leaves no checkpoint and no
// temporary file.
TEST_F(MpiRun, WriteFailingOnOneRankExitsTwoOnEveryRankAndLeavesNoFile) {
  const std::string scene = dir.write("scene.toml", scene_text("m5", "", ""));
  const std::string ck = dir.file("ck.h5");
  const Ran r = shell(mpirun(2) +
                      "--mca btl self,tcp sh -c 'if [ $OMPI_COMM_WORLD_RANK = 1 ]; then ulimit -f "
                      "64; fi; exec " +
                      DRUMLAB_MPI_CLI + " run " + scene + " --steps 10 --checkpoint " + ck + "'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("drumlab-mpi: error: " + ck + ": write failed (disk full?) in dataset"),
            std::string::npos)
      << r.output;
  for (const auto& e : std::filesystem::directory_iterator(tmp.path())) {
    EXPECT_EQ(e.path().filename().string().rfind("ck.h5", 0), std::string::npos) << e.path();
  }
}

}  // namespace
}  // namespace drumlab::test
