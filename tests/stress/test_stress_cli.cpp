// `drumlab stress --quick`: every cheap stress case must pass (the suite's own assertions), and
// the table and CSV must say so. Two cases made to misbehave for real show that the suite names
// a misbehaving case and fails: a child `drumlab run` on a full disk (ulimit -f) exits 2 where its
// case expects 0 or 3, and a case whose folder cannot be made throws.
#include <gtest/gtest.h>

#include <filesystem>
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

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// What a misbehaving case must leave: its table row with its name and FAIL, the count, the CSV
// row with pass = 0, and exit 1 with one line saying how many misbehaved.
void expect_reported_failure(const CliResult& r, const std::filesystem::path& out,
                             const std::string& name, const std::string& observed) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("| " + name + " |"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(observed), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| FAIL |"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0 of 1 cases pass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("drumlab: failed: 1 of 1 stress cases misbehaved"), std::string::npos)
      << r.output;
  const std::string csv = read_text(out / "stress.csv");
  EXPECT_NE(csv.find("\"" + name + "\""), std::string::npos) << csv;
  EXPECT_NE(csv.find(",0,"), std::string::npos) << csv;  // pass = 0
}

// A full disk for the whole suite (sh's ulimit -f: 512-byte blocks, 64 kB): the table, the CSV
// and the case's scene fit, the child run's HDF5 series does not, so the child exits 2 with a
// write error, which the stability case does not allow (exit 0 with sane files, or exit 3).
TEST(StressCli, ChildExitingWithAnErrorIsReportedAndFailsTheSuite) {
  TempDir dir("stress-full-disk");
  const CliResult r =
      run_shell("sh -c 'ulimit -f 128; exec " + std::string(DRUMLAB_CLI) +
                " stress --only \"dt = 1 x Rayleigh\" --out " + dir.path().string() + "'");
  expect_reported_failure(r, dir.path(), "dt = 1 x Rayleigh", "exit 2: drumlab: error:");
}

// The case's folder cannot be made (a file is where it goes): the case throws, its row says so,
// and the suite still writes its table and CSV and fails.
TEST(StressCli, CaseThatThrowsIsReportedAndFailsTheSuite) {
  TempDir dir("stress-throws");
  std::filesystem::create_directories(dir.path() / "work");
  dir.write("work/inputs", "a file where the cases' folder goes\n");
  const CliResult r = run_cli("stress --only 'scene NaN' --out " + dir.path().string());
  expect_reported_failure(r, dir.path(), "scene NaN", "threw: ");
}

}  // namespace
}  // namespace drumlab::test
