// `drumlab run` and `drumlab info` end to end: a small drum runs and reports; bad scenes and a time
// step above the stability limit give one-line errors with exit code 2; a forced unstable run stops
// with exit code 3 and says why.
#include <gtest/gtest.h>

#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

TEST(CliRun, SmallDrumRunsAndReportsThroughput) {
  TempDir dir("run");
  const auto scene = dir.write("small.toml", small_drum_scene());
  for (const char* method : {"m1", "m2", "m3", "m4", "m5", "brute", "mlgrid", "verlet", "auto"}) {
    const auto r = run_cli("run " + scene.string() + " --method " + method);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("particle-steps/s"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("outside drum 0, non-finite 0"), std::string::npos) << r.output;
  }
}

TEST(CliRun, BadScenesGiveOneLineErrors) {
  TempDir dir("run-bad");
  struct Case {
    std::string name, text, args, expected;
  };
  std::string negative = small_drum_scene();
  negative.replace(negative.find("radius = 0.004"), 14, "radius = -0.004");
  std::string unknown_key = small_drum_scene();
  unknown_key.replace(unknown_key.find("omega = 2.0"), 11, "omgea = 2.0");
  const std::vector<Case> cases = {
      {"negative.toml", negative, "", "radius"},
      {"typo.toml", unknown_key, "", "omgea"},
      {"method.toml", small_drum_scene(), "--method m6", "unknown search method 'm6'"},
      {"bigdt.toml", small_drum_scene("dt = 0.01\nduration = 0.01"), "",
       "above the stability limit"},
      {"paper.toml", "", "", "cannot read scene file"},
      // CLI11 2.1 reads "-3" into an unsigned as 2^64 - 3: a run of forever (found by fuzzing).
      {"steps.toml", small_drum_scene(), "--steps -3", "--steps"},
  };
  for (const Case& c : cases) {
    const auto path = c.text.empty() ? dir.path() / c.name : dir.write(c.name, c.text);
    const auto r = run_cli("run " + path.string() + " " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find("drumlab: error: "), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("particle-steps/s"), std::string::npos) << "ran anyway: " << r.output;
  }
  const auto paper = run_cli(std::string("run ") + DRUMLAB_SCENES_DIR + "/paper_table1.toml");
  EXPECT_EQ(paper.exit_code, 2) << paper.output;
  EXPECT_NE(paper.output.find("fill.kind"), std::string::npos) << paper.output;
}

TEST(CliRun, TimeStepFarAboveTheLimitStopsAsUnstable) {
  TempDir dir("run-unstable");
  // dt = 20 Rayleigh times, forced with --unsafe-dt: the run must stop with a reason, exit 3.
  const auto scene =
      dir.write("unstable.toml", small_drum_scene("dt_factor = 1.0\nduration = 0.5"));
  const auto r = run_cli("run " + scene.string() + " --unsafe-dt --dt-factor 20");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("drumlab: unstable: "), std::string::npos) << r.output;
  // Whichever check catches it first (the health check or the search), the line says what to do
  // and what dt was.
  EXPECT_NE(r.output.find("try a smaller time.dt (now "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("= 20 Rayleigh times)"), std::string::npos) << r.output;
}

// `--steps 0` fills and settles only (LAMMPS's `run 0`): it must not fall back to the scene's
// duration, and a checkpoint written then restarts at step 0 of the turning phase.
TEST(CliRun, ZeroStepsOnlyFillsAndSettles) {
  TempDir dir("run-zero");
  const auto scene = dir.write("small.toml", small_drum_scene());
  const auto file = dir.path() / "filled.h5";
  const auto r = run_cli("run " + scene.string() + " --steps 0 --checkpoint " + file.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("then turn 0 steps"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("checkpoint        " + file.string()), std::string::npos) << r.output;
  const auto again =
      run_cli("run " + scene.string() + " --restart " + file.string() + " --steps 5");
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("particle-steps/s"), std::string::npos) << again.output;
}

TEST(CliInfo, EveryShippedSceneHasInfo) {
  for (const char* scene : {"drum_demo", "drum_paper", "paper_table1", "paper_table2",
                            "teach_stencil", "tilted_drum", "mono_periodic"}) {
    const auto r = run_cli(std::string("info ") + DRUMLAB_SCENES_DIR + "/" + scene + ".toml");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("Rayleigh time"), std::string::npos) << r.output;
  }
  const auto demo = run_cli(std::string("info ") + DRUMLAB_SCENES_DIR + "/drum_demo.toml");
  EXPECT_NE(demo.output.find("18825"), std::string::npos) << demo.output;
  EXPECT_NE(demo.output.find("Froude number     0.04587"), std::string::npos) << demo.output;
}

// With `search = "auto"` the memory estimate is for the method auto picks (the one a run uses),
// not for a fixed stand-in.
TEST(CliInfo, MemoryEstimateIsForAutosPick) {
  const auto r = run_cli(std::string("info ") + DRUMLAB_SCENES_DIR + "/mercury_wet_drum.toml");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string picked = "search method     auto -> ";
  const std::size_t at = r.output.find(picked);
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::size_t from = at + picked.size();
  const std::string method = r.output.substr(from, r.output.find(' ', from) - from);
  const std::size_t line = r.output.find("memory estimate");
  ASSERT_NE(line, std::string::npos) << r.output;
  const std::string memory = r.output.substr(line, r.output.find('\n', line) - line);
  EXPECT_NE(memory.find("; for auto's pick " + method + ")"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace drumlab::test
