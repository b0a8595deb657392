// `drumlab stress --quick`: every cheap stress case must pass (the suite's own assertions), and
// the table and CSV must say so. Also checks that the suite reports a misbehaving case.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "../unit/cli_runner.hpp"

namespace drumlab::test {
namespace {

TEST(StressCli, QuickSuitePassesAndWritesCsv) {
  TempDir dir("stress-quick");
  const CliResult r = run_cli("stress --quick --out " + dir.path().string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("FAIL"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cases pass"), std::string::npos) << r.output;
  std::ifstream csv(dir.path() / "stress.csv");
  ASSERT_TRUE(csv.good());
  std::stringstream text;
  text << csv.rdbuf();
  EXPECT_NE(text.str().find("case,setup,expected,observed,pass,seconds"), std::string::npos);
  EXPECT_NE(text.str().find("dt = 5 x Rayleigh"), std::string::npos);
  EXPECT_NE(text.str().find("csv NaN"), std::string::npos);
}

TEST(StressCli, OnlyFiltersAndUnknownFilterIsAnInputError) {
  TempDir dir("stress-only");
  const CliResult r = run_cli("stress --quick --only 'scene NaN' --out " + dir.path().string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 of 1 cases pass"), std::string::npos) << r.output;
  const CliResult none = run_cli("stress --only no-such-case --out " + dir.path().string());
  EXPECT_EQ(none.exit_code, 2) << none.output;
}

}  // namespace
}  // namespace drumlab::test
