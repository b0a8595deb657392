// The agglomerate outputs end to end: the HDF5 series stores the bond graph of a wet drum and
// reads it back; `run --agglomerates` writes its table through a .part file and a chart beside
// it; `analyze` of the run's series gives the same table byte for byte, and the table reads back
// (a damaged one: one line naming file and line); a run killed with SIGKILL
// leaves a series whose complete frames and sidecar open; a dry scene's series has no bond graph
// and `analyze` refuses it with one line.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "engine/analysis/agglomerate_table.hpp"
#include "engine/analysis/agglomerates.hpp"
#include "engine/io/h5_file.hpp"
#include "engine/io/h5_series.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t c = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++c;
  return c;
}

TEST(AgglomerateOutputs, SeriesStoresTheBondGraphOfAWetDrum) {
  TempDir dir("agglo-series");
  const SceneConfig scene = parse_scene(wet_output_scene_text(), "wet");
  auto sim = settled_simulation(scene, 300);
  std::vector<Bond> bonds;
  const AgglomerateInput in = agglomerate_input(*sim, bonds);
  ASSERT_GT(bonds.size(), 10u);
  const AgglomerateFrame frame = find_agglomerates(in, {});
  const auto file = dir.path() / "wet.h5";
  {
    H5Series series(file);
    const SeriesBondFrame b{series_bond_rows(sim->particles(), bonds), frame.label, 0.0,
                            scene.drum.omega};
    series.write_frame(sim->particles(), sim->time(), sim->steps(), &b);
    series.finish();
  }
  const SeriesInfo info = read_series_info(file);
  EXPECT_EQ(info.frames, 1u);
  EXPECT_TRUE(info.complete);
  EXPECT_TRUE(info.has_bonds);
  const SeriesFrame f = read_series_frame(file, 0);
  ASSERT_EQ(f.bonds.size(), bonds.size());
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    EXPECT_EQ(f.bonds[k].i, bonds[k].i);
    EXPECT_EQ(f.bonds[k].j, bonds[k].j);
    EXPECT_EQ(f.bonds[k].volume, bonds[k].volume);
    EXPECT_EQ(f.bonds[k].force, bonds[k].force);
    EXPECT_EQ(f.bonds[k].age, bonds[k].age);
  }
  EXPECT_EQ(f.mass, sim->particles().mass);
  EXPECT_EQ(f.drum_omega, scene.drum.omega);
  h5::Handle h = h5::open_file(file);
  EXPECT_EQ(h5::read_u32(h.get(), "frame_000000/agglomerate_id", sim->particles().size()),
            frame.label);
  EXPECT_EQ(h5::read_doubles(h.get(), "frame_000000/liquid_volume", sim->particles().size()),
            std::vector<double>(sim->particles().size(), 0.0));  // no film array: 0
  const std::string x = read_text(dir.path() / "wet.xdmf");
  EXPECT_EQ(count_of(x, "/frame_000000/agglomerate_id"), 1u);
  EXPECT_EQ(count_of(x, "/frame_000000/liquid_volume"), 1u);

  // With a film array (liquid migration registers one), liquid_volume is the film.
  Particles with_film = sim->particles();
  std::vector<double>& film = with_film.add_array(kLiquidFilmArray);
  for (std::size_t i = 0; i < film.size(); ++i) film[i] = 1e-12 * static_cast<double>(i);
  {
    H5Series series(dir.path() / "film.h5");
    const SeriesBondFrame b{series_bond_rows(sim->particles(), bonds), frame.label, 0.0,
                            scene.drum.omega};
    series.write_frame(with_film, sim->time(), sim->steps(), &b);
    series.finish();
  }
  EXPECT_EQ(read_series_frame(dir.path() / "film.h5", 0).film, film);
}

TEST(AgglomerateOutputs, AnalyzeOfTheRunsSeriesEqualsTheRunsTable) {
  TempDir dir("agglo-cli");
  const std::string scene = dir.write("wet.toml", wet_output_scene_text()).string();
  const std::string d = dir.path().string() + "/";
  auto r = run_cli("run " + scene + " --steps 240 --every 40 --granule-age 0.004 --h5 " + d +
                   "s.h5 --agglomerates " + d + "run.csv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("agglomerates      7 frames"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(d + "run.csv.part"));
#if DRUMLAB_TESTS_RENDER
  ASSERT_TRUE(std::filesystem::exists(d + "run.png"));
  EXPECT_GT(std::filesystem::file_size(d + "run.png"), 1000u);
#else  // a build without VTK draws no chart
  EXPECT_FALSE(std::filesystem::exists(d + "run.png"));
#endif
  const std::string table = read_text(d + "run.csv");
  EXPECT_EQ(count_of(table, "\n"), 8u) << table;  // header + frames 0, 40, ..., 240
  EXPECT_EQ(count_of(table, ",bond_age>=0.004s,"), 7u) << table;

  r = run_cli("analyze " + d + "s.h5 --granule-age 0.004 --agglomerates " + d + "analyze.csv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_text(d + "analyze.csv"), table);
  EXPECT_EQ(std::filesystem::exists(d + "analyze.png"), DRUMLAB_TESTS_RENDER != 0);
  // The last row of a wet drum has bonds and agglomerates; plain components at least as large.
  r = run_cli("analyze " + d + "s.h5 --granule-age 0 --agglomerates " + d + "plain.csv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(count_of(read_text(d + "plain.csv"), ",components,"), 7u);
  // Communities of the force network: the CSV says which criterion; no community is larger than
  // the largest plain component.
  r = run_cli("analyze " + d + "s.h5 --granule-criterion community --agglomerates " + d +
              "community.csv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<AgglomerateStats> communities = read_agglomerate_table(d + "community.csv");
  ASSERT_EQ(communities.size(), 7u);
  for (const AgglomerateStats& row : communities) {
    EXPECT_EQ(row.criterion, "community(resolution=1)");
    EXPECT_LE(static_cast<double>(row.largest), row.largest_plain_share * 250.0 + 1e-9);
  }
  r = run_cli("analyze " + d + "s.h5 --granule-criterion community --granule-age 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--granule-age applies to --granule-criterion age, not community"),
            std::string::npos)
      << r.output;
  r = run_cli("analyze " + d + "s.h5 --granule-resolution 2 --agglomerates " + d + "x.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--granule-resolution applies to --granule-criterion community"),
            std::string::npos)
      << r.output;
  r = run_cli("analyze " + d + "s.h5 --granule-criterion louvain");
  EXPECT_EQ(r.exit_code, 2) << r.output;

  // The table read back gives the rows it was written from (drumlab analyze TABLE.csv charts it).
  const std::vector<AgglomerateStats> rows = read_agglomerate_table(d + "run.csv");
  ASSERT_EQ(rows.size(), 7u);
  std::string again = agglomerate_csv_header() + "\n";
  for (const AgglomerateStats& row : rows) again += agglomerate_csv_row(row) + "\n";
  EXPECT_EQ(again, table);
  std::filesystem::remove(d + "run.png");
  r = run_cli("analyze " + d + "run.csv");
#if DRUMLAB_TESTS_RENDER
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(std::filesystem::file_size(d + "run.png"), 1000u);
#else
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("run.csv: this build has no VTK to draw the chart"), std::string::npos)
      << r.output;
#endif
}

TEST(AgglomerateOutputs, DamagedTableIsOneLineNamingFileAndLine) {
  TempDir dir("agglo-table");
  const std::string header = agglomerate_csv_header() + "\n";
  const std::string good =
      "0.5,components,2,2.5,3,0.001,0.002,0.003,4,1e-9,2e-9,0,0.5,3e-9,0,0,1e-10\n";
  EXPECT_EQ(read_agglomerate_table(dir.write("ok.csv", header + good)).size(), 1u);
  EXPECT_EQ(read_agglomerate_table(dir.path() / "ok.csv")[0].spray.sprayed, 3e-9);
  EXPECT_EQ(read_agglomerate_table(dir.path() / "ok.csv")[0].spray.on_wall, 1e-10);
  // A table written before the wall film's column still reads, its wall film 0.
  const std::string spray_header =
      "time,criterion,agglomerates,mean_size,largest,d10,d50,d90,bonds,free_liquid,"
      "bridge_liquid,wall_bridge_liquid,largest_plain_share,sprayed_liquid,airborne_liquid,"
      "lost_liquid\n";
  const auto before = read_agglomerate_table(dir.write(
      "before.csv",
      spray_header + "0.5,components,2,2.5,3,0.001,0.002,0.003,4,1e-9,2e-9,0,0.5,3e-9,0,1e-10\n"));
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].spray.lost, 1e-10);
  EXPECT_EQ(before[0].spray.on_wall, 0.0);
  // A table written before the spray's columns still reads, its spray terms 0.
  const std::string old_header =
      "time,criterion,agglomerates,mean_size,largest,d10,d50,d90,bonds,free_liquid,"
      "bridge_liquid,wall_bridge_liquid,largest_plain_share\n";
  const auto old = read_agglomerate_table(dir.write(
      "old.csv", old_header + "0.5,components,2,2.5,3,0.001,0.002,0.003,4,1e-9,2e-9,0,0.5\n"));
  ASSERT_EQ(old.size(), 1u);
  EXPECT_EQ(old[0].free_liquid, 1e-9);
  EXPECT_EQ(old[0].spray, SprayLiquid{});
  for (const auto& [text, where] :
       {std::pair<std::string, std::string>{"time,x\n" + good, "bad.csv:1:"},
        {header + good + "0.5,components,2,2.5\n", "bad.csv:3:"},
        {header + "0.5,components,two,2.5,3,0.001,0.002,0.003,4,1e-9,2e-9,0,0.5,0,0,0,0\n",
         "bad.csv:2:"},
        {header + "0.5,components,2,2.5,3,0.001,0.002,0.003,4,1e-9,2e-9,0,0.5\n", "bad.csv:2:"},
        {header, "bad.csv: the table has no rows"}}) {
    const auto file = dir.write("bad.csv", text);
    try {
      read_agglomerate_table(file);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
    const auto r = run_cli("analyze " + file.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(count_of(r.output, "\n"), 1u) << r.output;
  }
}

TEST(AgglomerateOutputs, DrySeriesHasNoBondGraphAndAnalyzeRefusesIt) {
  TempDir dir("agglo-dry");
  const std::string scene = dir.write("dry.toml", output_scene_text()).string();
  const std::string d = dir.path().string() + "/";
  auto r = run_cli("run " + scene + " --steps 20 --every 10 --h5 " + d + "dry.h5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  h5::Handle h = h5::open_file(d + "dry.h5");
  EXPECT_FALSE(h5::exists(h.get(), "frame_000000/bonds"));
  EXPECT_FALSE(h5::exists(h.get(), "frame_000000/agglomerate_id"));
  EXPECT_EQ(read_text(d + "dry.xdmf").find("agglomerate_id"), std::string::npos);
  r = run_cli("analyze " + d + "dry.h5 --agglomerates " + d + "a.csv");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("has no bond graph"), std::string::npos) << r.output;
  EXPECT_EQ(count_of(r.output, "\n"), 1u) << r.output;
  EXPECT_FALSE(std::filesystem::exists(d + "a.csv"));
  EXPECT_FALSE(std::filesystem::exists(d + "a.csv.part"));
  r = run_cli("analyze " + d + "none.h5 --agglomerates " + d + "a.csv");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_cli("run " + scene + " --steps 20 --agglomerates " + d + "no/such/a.csv");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--agglomerates"), std::string::npos) << r.output;
}

// A real SIGKILL: the run is a child process, read while it streams, killed once its sidecar
// lists five frames.
TEST(AgglomerateOutputs, SeriesOfARunKilledWithSigkillOpens) {
  TempDir dir("agglo-kill");
  const std::string scene = dir.write("wet.toml", wet_output_scene_text()).string();
  const std::string h5 = dir.path().string() + "/killed.h5";
  const std::string xdmf = dir.path().string() + "/killed.xdmf";
  const std::string csv = dir.path().string() + "/killed.csv";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::freopen("/dev/null", "w", stdout);
    ::execl(DRUMLAB_CLI, DRUMLAB_CLI, "run", scene.c_str(), "--steps", "1000000", "--every", "10",
            "--h5", h5.c_str(), "--agglomerates", csv.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::size_t listed = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (std::filesystem::exists(xdmf)) listed = count_of(read_text(xdmf), "<Time Value=");
    // A reader opening the file while it streams (ParaView, h5ls) must not stop the writer; its
    // read may fail if it lands in the middle of a frame.
    try {
      if (listed >= 1) (void)read_series_info(h5);
    } catch (const InputError&) {
    }
    if (listed >= 5) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the run ended by itself";
  ASSERT_GE(listed, 5u) << "the run wrote fewer than 5 frames in 60 s";

  const SeriesInfo info = read_series_info(h5);
  EXPECT_FALSE(info.complete);
  EXPECT_TRUE(info.has_bonds);
  const std::string x = read_text(xdmf);
  const std::size_t in_sidecar = count_of(x, "<Time Value=");
  EXPECT_GE(in_sidecar, 5u);
  EXPECT_GE(info.frames, in_sidecar);  // the sidecar follows the file's flush
  EXPECT_LE(info.frames, in_sidecar + 1);
  const std::uint64_t first_step = read_series_frame(h5, 0).step;
  for (std::size_t k = 0; k < info.frames; ++k) {
    const SeriesFrame f = read_series_frame(h5, k);
    EXPECT_EQ(f.step, first_step + 10 * k) << k;
    EXPECT_EQ(f.position.size(), 250u);
  }
  // Every dataset the sidecar names exists with the stated size.
  h5::Handle f = h5::open_file(h5);
  const std::regex item(
      R"re(<DataItem Dimensions="(\d+)( 3)?"[^>]*>killed\.h5:(/[^<]+)</DataItem>)re");
  std::size_t items = 0;
  for (auto it = std::sregex_iterator(x.begin(), x.end(), item); it != std::sregex_iterator();
       ++it, ++items) {
    const std::size_t n = std::stoul((*it)[1]) * ((*it)[2].matched ? 3 : 1);
    EXPECT_EQ(h5::element_count(f.get(), (*it)[3]), n) << (*it)[3];
  }
  EXPECT_EQ(items, 8u * in_sidecar);
  // The table was never finished: only its .part file, never a complete-looking killed.csv.
  EXPECT_FALSE(std::filesystem::exists(csv));
  EXPECT_TRUE(std::filesystem::exists(csv + ".part"));
}

}  // namespace
}  // namespace drumlab::test
