// `drumlab contacts` end to end: right answers on awkward inputs, clear errors on bad ones.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CliContacts, WritesSortedPairsForEveryMethod) {
  TempDir dir("contacts");
  // Three touching spheres in a row (0-1, 1-2 touch exactly) and one far away.
  const auto csv =
      dir.write("p.csv", "x,y,z,r\n0.02,0,0,0.01\n0,0,0,0.01\n0.04,0,0,0.01\n9,9,9,0.01\n");
  for (const char* method : {"brute", "m1", "m2", "m3", "m4", "m5"}) {
    const auto out = dir.path() / (std::string(method) + ".csv");
    const auto r = run_cli("contacts --particles " + csv.string() + " --method " + method +
                           " --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(read(out), "i,j\n0,1\n0,2\n") << method;
    EXPECT_NE(r.output.find("2 contacts"), std::string::npos) << r.output;
  }
}

TEST(CliContacts, SingleParticleAndFarApartParticles) {
  TempDir dir("contacts-far");
  const auto one = dir.write("one.csv", "x,y,z,r\n1,2,3,0.001\n");
  auto r = run_cli("contacts --particles " + one.string() + " --method m3");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("0 contacts"), std::string::npos) << r.output;
  // Tiny spheres 1e6 m apart: a dense grid would need ~1e27 cells.
  const auto far =
      dir.write("far.csv", "x,y,z,r\n0,0,0,0.001\n1e6,1e6,1e6,0.001\n0.0015,0,0,0.001\n");
  r = run_cli("contacts --particles " + far.string() + " --method m3");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("i,j\n0,2\n"), std::string::npos) << r.output;
}

TEST(CliContacts, BadInputGivesOneLineErrorAndExitCode2) {
  TempDir dir("contacts-bad");
  const auto bad = dir.write("bad.csv", "x,y,z,r\n0,0,0,-1\n");
  auto r = run_cli("contacts --particles " + bad.string() + " --method m1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bad.csv:2: column 'r': radius -1 must be positive"), std::string::npos)
      << r.output;

  const auto good = dir.write("good.csv", "x,y,z,r\n0,0,0,1\n");
  r = run_cli("contacts --particles " + good.string() + " --method m9");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("unknown search method 'm9'"), std::string::npos) << r.output;

  r = run_cli("contacts --particles " + (dir.path() / "missing.csv").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("cannot read particle file"), std::string::npos) << r.output;

  r = run_cli("contacts --particles " + good.string() + " --out /nonexistent-dir/pairs.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("/nonexistent-dir/pairs.csv: cannot write"), std::string::npos)
      << r.output;

  // Coordinates so large that no grid can index them: a clear error, not a crash.
  const auto huge = dir.write("huge.csv", "x,y,z,r\n0,0,0,0.001\n1e300,0,0,0.001\n");
  r = run_cli("contacts --particles " + huge.string() + " --method m1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("too many to index"), std::string::npos) << r.output;
  r = run_cli("contacts --particles " + huge.string() + " --method brute");
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

}  // namespace
}  // namespace drumlab::test
