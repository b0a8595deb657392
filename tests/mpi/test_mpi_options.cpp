// drumlab-mpi takes `drumlab run`'s options (app/run/): the same errors for contradicting flags
// (exit 2, one line, in both executables), --agglomerates, --team and --unsafe-dt under mpirun
// with the serial run's results and summary lines; and an input error that one rank alone meets
// (its part of a checkpoint refused at the start) ends every rank with one line and exit 2,
// never a hang.
#include <gtest/gtest.h>

#include <string>

#include "engine/io/checkpoint.hpp"
#include "tests/mpi/mpi_runner.hpp"
#include "tests/same_bits.hpp"
#include "tests/small_drum_text.hpp"

namespace drumlab::test {
namespace {

/// 300 particles, a short settling.
std::string small_scene() {
  SmallDrumText t;
  t.fill = "count = 300\nsettle_time = 0.002\nseed = 3";
  t.gravity = "[0.0, -150.0, 0.0]";
  t.output = "diagnostics_every = 50";
  return t.text();
}

/// How often `what` occurs in `text`.
std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

/// The line of `text` that starts with `label` ("" if none).
std::string line(const std::string& text, const std::string& label) {
  const std::string lines = "\n" + text;
  const std::size_t at = lines.find("\n" + label);
  if (at == std::string::npos) return {};
  return lines.substr(at + 1, lines.find('\n', at + 1) - at - 1);
}

class MpiOptions : public MpiCase {};

TEST_F(MpiOptions, ContradictingFlagsAreOneLineAndExitTwoInBothExecutables) {
  const std::string scene = dir.write("scene.toml", small_scene());
  const std::string ck = " --checkpoint " + dir.file("c.h5");
  for (const auto& [args, flag] :
       {std::pair<std::string, std::string>{"--checkpoint-every 10", "--checkpoint-every"},
        {"--every 10" + ck, "--every"},
        {"--method nope", "--method"},
        {"--granule-criterion community --granule-age 1", "--granule-age"}}) {
    const Ran serial = shell(std::string(DRUMLAB_CLI) + " run " + scene + " --steps 5 " + args);
    EXPECT_EQ(serial.exit_code, 2) << serial.output;
    EXPECT_EQ(count(serial.output, "drumlab: error: " + flag), 1u) << serial.output;
    const Ran mpi = shell(mpirun(2) + "--timeout 60 " + DRUMLAB_MPI_CLI + " run " + scene +
                          " --steps 5 " + args);
    EXPECT_EQ(mpi.exit_code, 2) << mpi.output;
    EXPECT_EQ(count(mpi.output, "drumlab-mpi: error: " + flag), 1u) << mpi.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.h5")));
  // The grid occupancy needs the one search grid a decomposed run does not have.
  const Ran grid = shell(mpirun(2) + "--timeout 60 " + DRUMLAB_MPI_CLI + " run " + scene +
                         " --steps 5 --vtu " + dir.file("vtu") + " --grid-vtk");
  EXPECT_EQ(grid.exit_code, 2) << grid.output;
  EXPECT_EQ(count(grid.output, "drumlab-mpi: error: --grid-vtk: each rank searches its own box"),
            1u)
      << grid.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("vtu")));
  // Communities need the whole bond network, which a series written where the particles are
  // does not hold on one rank.
  const Ran community = shell(mpirun(2) + "--timeout 60 " + DRUMLAB_MPI_CLI + " run " + scene +
                              " --steps 5 --granule-criterion community --h5 " + dir.file("s.h5"));
  EXPECT_EQ(community.exit_code, 2) << community.output;
  EXPECT_EQ(count(community.output, "drumlab-mpi: error: --granule-criterion community: the ranks"),
            1u)
      << community.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.h5")));
  // Binder droplets are not decomposed yet.
  const std::string sprayed = dir.write(
      "spray.toml", small_scene() +
                        "[liquid]\nsurface_tension = 0.072\nliquid_content = 0.0\n"
                        "max_bridge_volume = 1e-9\n[[spray]]\nposition = [0.0, 0.0, 0.01]\n"
                        "direction = [0.0, -1.0, 0.0]\nrate = 1e-7\ndroplet_radius = 1e-4\n"
                        "droplet_speed = 1.0\n");
  const Ran spray =
      shell(mpirun(2) + "--timeout 60 " + DRUMLAB_MPI_CLI + " run " + sprayed + " --steps 5");
  EXPECT_EQ(spray.exit_code, 2) << spray.output;
  EXPECT_EQ(count(spray.output, "drumlab-mpi: error: [[spray]]: not on drumlab-mpi yet"), 1u)
      << spray.output;
}

// --agglomerates (the gathered state's table on rank 0, its chart), --observables, --team,
// --unsafe-dt and
// --checkpoint-every under mpirun: the serial run's table, checkpoint and summary lines.
TEST_F(MpiOptions, SharedOptionsGiveTheSerialRunsResults) {
  const std::string scene = dir.write("scene.toml", small_scene());
  const std::string args =
      " --steps 40 --every 20 --team fixed --unsafe-dt --checkpoint-every 15 --agglomerates ";
  const Ran s = shell(std::string(DRUMLAB_CLI) + " run " + scene + " --threads 1" + args +
                      dir.file("serial.csv") + " --observables " + dir.file("serial_obs.csv") +
                      " --checkpoint " + dir.file("serial.h5"));
  ASSERT_EQ(s.exit_code, 0) << s.output;
  const SimulationState want = read_checkpoint(dir.file("serial.h5")).state;
  const SimulationState got = parallel(
      2, scene, args + dir.file("mpi.csv") + " --observables " + dir.file("mpi_obs.csv"), "mpi.h5");
  EXPECT_TRUE(same_bits(want.particles.position, got.particles.position));
  EXPECT_TRUE(same_bits(want.particles.velocity, got.particles.velocity));
  EXPECT_EQ(want.steps, got.steps);
  const std::string table = read_text(dir.file("serial.csv"));
  EXPECT_EQ(count(table, "\n"), 4u) << table;  // the header and frames 0, 20, 40
  EXPECT_EQ(read_text(dir.file("mpi.csv")), table);
  const std::string observables = read_text(dir.file("serial_obs.csv"));
  EXPECT_EQ(count(observables, "\n"), 4u) << observables;
  EXPECT_EQ(read_text(dir.file("mpi_obs.csv")), observables);
  // The chart, drawn by the drumlab beside drumlab-mpi (which links no VTK) from the table.
  EXPECT_NE(last_output.find("agglomerate chart " + dir.file("mpi.png")), std::string::npos)
      << last_output;
  EXPECT_GT(std::filesystem::file_size(dir.file("mpi.png")), 1000u);
  for (const std::string label : {"scene ", "plan ", "particles ", "steps ", "search method "}) {
    EXPECT_FALSE(line(s.output, label).empty()) << label << s.output;
    EXPECT_EQ(line(last_output, label), line(s.output, label)) << last_output;
  }
  // Checkpoints at turning steps 15 and 30, and the last at 40: three written.
  EXPECT_NE(last_output.find("output            3 checkpoint(s)"), std::string::npos)
      << last_output;
}

// A checkpoint with one particle outside the drum: read in shares (a named method), only the rank
// that owns it refuses its part at the start; read by rank 0 ("auto"), rank 0 alone refuses the
// state. Either way every rank stops, exit 2, with one line.
TEST_F(MpiOptions, InputErrorOfOneRankStopsEveryRankWithOneLine) {
  const std::string scene = dir.write("scene.toml", small_scene());
  serial(scene, "--steps 5", "ok.h5");
  Checkpoint c = read_checkpoint(dir.file("ok.h5"));
  c.state.particles.position.back() = Vec3(0.3, 0.0, 0.025);  // the drum's radius is 0.1 m
  const std::string bad = dir.file("bad.h5");
  write_checkpoint(bad, c.state, c.scene_name);
  for (const std::string method : {" --method m5", " --method auto"}) {
    const Ran r = shell(mpirun(3) + "--timeout 60 " + DRUMLAB_MPI_CLI + " run " + scene +
                        " --steps 5 --restart " + bad + method);
    EXPECT_EQ(r.exit_code, 2) << method << ": " << r.output;
    EXPECT_EQ(count(r.output, "drumlab-mpi: error: "), 1u) << method << ": " << r.output;
    EXPECT_NE(r.output.find("outside the drum"), std::string::npos) << method << ": " << r.output;
  }
}

// An error that one rank alone meets: the scene file, or the checkpoint's directory, missing on
// rank 1 only (each rank given its own arguments, as where nodes see different disks). The scene
// is read under an agreement (rank 0 prints rank 1's line); the directory is checked by each rank
// alone, and rank 1, finding no other rank failing with it, prints its line and stops every rank
// (MPI_Abort). Either way: exit 2, one line naming the file, no hang.
TEST_F(MpiOptions, ErrorOfOneRankAloneStopsEveryRankWithOneLine) {
  const std::string scene = dir.write("scene.toml", small_scene());
  const std::string missing = dir.file("missing");
  const std::string ck = " --steps 5 --checkpoint ";
  for (const auto& [rank0, rank1] :
       {std::pair{scene, missing + ".toml"},
        std::pair{scene + ck + dir.file("c.h5"), scene + ck + missing + "/c.h5"}}) {
    const std::string run = std::string("exec ") + DRUMLAB_MPI_CLI + " run ";
    const Ran r = shell(mpirun(2) + "--timeout 60 sh -c 'if [ $OMPI_COMM_WORLD_RANK = 1 ]; then " +
                        run + rank1 + "; else " + run + rank0 + "; fi'");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(count(r.output, "drumlab-mpi: error: "), 1u) << r.output;
    EXPECT_NE(r.output.find(missing), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace drumlab::test
