// engine/openmp_waiting.hpp: `--threads N` with N > 1 makes drumlab run with
// OMP_WAIT_POLICY=passive (it executes itself again with the variable set) unless the user chose
// how threads wait; one thread, or DRUMLAB_OMP_DEFAULT=off, leaves the runtime's default. Read from
// the run summary's "waiting:" line, which reports the variables the process runs with.
#include <gtest/gtest.h>

#include "engine/openmp_waiting.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

TEST(OpenmpWaiting, AsksForThreadsOnlyAboveOne) {
  const auto asks = [](std::vector<std::string> args) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    return asks_for_threads(static_cast<int>(argv.size()), argv.data());
  };
  EXPECT_TRUE(asks({"drumlab", "run", "s.toml", "--threads", "2"}));
  EXPECT_TRUE(asks({"drumlab", "run", "--threads=4", "s.toml"}));
  EXPECT_FALSE(asks({"drumlab", "run", "s.toml", "--threads", "1"}));
  EXPECT_FALSE(asks({"drumlab", "run", "s.toml"}));
  EXPECT_FALSE(asks({"drumlab", "run", "s.toml", "--threads"}));
}

TEST(OpenmpWaiting, MoreThreadsSleepAtBarriersUnlessTheUserChose) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP";
#endif
  TempDir dir("openmp-waiting");
  const auto scene = dir.write("small.toml", small_drum_scene());
  const std::string run = "run " + scene.string() + " --steps 5 --settle-time 0";
  const std::string clear = "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u DRUMLAB_OMP_DEFAULT ";
  const auto waiting = [&](const std::string& env, const std::string& threads) {
    const CliResult r =
        run_shell(clear + env + " " + DRUMLAB_CLI + " " + run + " --threads " + threads);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const auto at = r.output.find("waiting: ");
    return at == std::string::npos ? std::string("(no waiting line)")
                                   : r.output.substr(at, r.output.find('\n', at) - at);
  };
  EXPECT_NE(waiting("", "2").find("OMP_WAIT_POLICY=passive"), std::string::npos);
  EXPECT_NE(waiting("", "1").find("runtime's default"), std::string::npos);
  EXPECT_NE(waiting("DRUMLAB_OMP_DEFAULT=off", "2").find("runtime's default"), std::string::npos);
  EXPECT_NE(waiting("OMP_WAIT_POLICY=active", "2").find("not passive"), std::string::npos);
  EXPECT_NE(waiting("GOMP_SPINCOUNT=1000", "2").find("GOMP_SPINCOUNT"), std::string::npos);
}

}  // namespace
}  // namespace drumlab::test
