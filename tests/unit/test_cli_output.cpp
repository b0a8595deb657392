// `drumlab run` outputs end to end (no VTK needed): --h5 writes the series and its XDMF sidecar,
// --checkpoint/--restart continue a run bit-identically (N + N steps vs 2N, compared through the
// checkpoints), and bad output paths stop with exit code 2 before running, leaving no file.
#include <gtest/gtest.h>

#include <cstring>

#include "engine/io/checkpoint.hpp"
#include "engine/io/h5_file.hpp"
#include "tests/same_bits.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

TEST(CliOutput, RestartContinuesBitIdentically) {
  TempDir dir("cli-restart");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const std::string d = dir.path().string() + "/";
  // 120 turning steps straight; 60, then 60 more from the checkpoint (other frame chunking).
  auto r = run_cli("run " + scene + " --steps 120 --checkpoint " + d + "full.h5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("run " + scene + " --steps 60 --every 7 --h5 " + d + "s.h5 --checkpoint " + d +
              "half.h5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("run " + scene + " --restart " + d + "half.h5 --steps 60 --checkpoint " + d +
              "cont.h5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("settle 0 steps"), std::string::npos) << r.output;
  const SimulationState full = read_checkpoint(d + "full.h5").state;
  const SimulationState half = read_checkpoint(d + "half.h5").state;
  const SimulationState cont = read_checkpoint(d + "cont.h5").state;
  EXPECT_EQ(cont.steps, full.steps);
  EXPECT_EQ(cont.steps, half.steps + 60);
  EXPECT_TRUE(same_bits(cont.particles.position, full.particles.position));
  EXPECT_TRUE(same_bits(cont.particles.velocity, full.particles.velocity));
  EXPECT_TRUE(same_bits(cont.particles.omega, full.particles.omega));
  EXPECT_TRUE(same_bits(cont.contact_history, full.contact_history));
  EXPECT_EQ(std::memcmp(&cont.time, &full.time, sizeof(double)), 0);
  EXPECT_FALSE(same_bits(half.particles.position, full.particles.position));
}

TEST(CliOutput, H5SeriesHasOneFramePerScheduledStep) {
  TempDir dir("cli-h5");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const auto file = dir.path() / "series.h5";
  const auto r = run_cli("run " + scene + " --steps 40 --every 10 --h5 " + file.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(std::filesystem::exists(dir.path() / "series.xdmf"));
  h5::Handle f = h5::open_file(file);
  const std::vector<std::uint64_t> steps = h5::read_u64(f.get(), "step", 5);
  for (std::size_t k = 1; k < steps.size(); ++k) EXPECT_EQ(steps[k] - steps[k - 1], 10u);
  EXPECT_EQ(h5::element_count(f.get(), "frame_000004/position"), 3u * 250u);
}

TEST(CliOutput, BadOutputPathsStopBeforeRunning) {
  TempDir dir("cli-output-bad");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const std::string missing = (dir.path() / "missing").string();
  for (const std::string& args :
       {"--h5 " + missing + "/s.h5", "--checkpoint " + missing + "/c.h5",
        "--restart " + missing + "/c.h5", std::string("--checkpoint-every 10"),
        std::string("--every 10"), "--every 10 --checkpoint " + dir.path().string() + "/c.h5",
        "--restart " + scene,
        "--h5 " + dir.path().string() + "/x.h5 --checkpoint " + dir.path().string() + "/./x.h5"}) {
    const auto r = run_cli("run " + scene + " --steps 20 " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("drumlab: error: "), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("particle-steps/s"), std::string::npos) << "ran anyway: " << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(missing));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

TEST(CliOutput, FullDiskStopsWithExitCode2AndLeavesNoFile) {
  TempDir dir("cli-full-disk");
  const std::string scene = dir.write("drum.toml", output_scene_text()).string();
  const std::string d = dir.path().string() + "/";
  // ulimit -f (512-byte blocks in sh): writes past 32 kB fail as on a full disk.
  for (const std::string& out : {"--h5 " + d + "s.h5 --every 1", "--checkpoint " + d + "c.h5"}) {
    const std::string command = "sh -c 'ulimit -f 64; exec " + std::string(DRUMLAB_CLI) + " run " +
                                scene + " --steps 40 " + out + "' 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) output.append(buf, n);
    const int status = ::pclose(pipe);
    ASSERT_TRUE(WIFEXITED(status)) << output;
    EXPECT_EQ(WEXITSTATUS(status), 2) << output;
    EXPECT_NE(output.find("write failed (disk full?)"), std::string::npos) << output;
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

}  // namespace
}  // namespace drumlab::test
