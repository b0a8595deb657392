// The HDF5 time series: frames read back equal the particles written, the /time and /step
// datasets list the frames, and the XDMF sidecar is XDMF 3 with one Polyvertex grid per frame
// whose every DataItem names a dataset that exists in the file with the stated dimensions.
// The series streams: each frame is on disk (listed in /time, in the sidecar) once written; an
// unfinished series keeps its frames without the `complete` mark; a failed write leaves no file.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "engine/io/h5_file.hpp"
#include "engine/io/h5_series.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/file_size_limit.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(H5Series, FramesRoundTripAndXdmfReferencesExistingDatasets) {
  TempDir dir("h5-series");
  const SceneConfig scene = output_scene();
  auto sim = settled_simulation(scene, 20);
  const auto file = dir.path() / "series.h5";
  std::vector<Particles> written;
  std::vector<double> times;
  {
    H5Series series(file);
    for (int k = 0; k < 3; ++k) {
      series.write_frame(sim->particles(), sim->time(), sim->steps());
      written.push_back(sim->particles());
      times.push_back(sim->time());
      sim->advance(25);
    }
    // Streamed: the frames so far are on disk before finish(), not yet marked complete.
    const SeriesInfo before = read_series_info(file);
    EXPECT_EQ(before.frames, 3u);
    EXPECT_FALSE(before.complete);
    EXPECT_FALSE(before.has_bonds);
    EXPECT_NE(read_text(dir.path() / "series.xdmf").find(h5_frame_group(2)), std::string::npos);
    series.finish();
  }
  ASSERT_TRUE(std::filesystem::exists(file));
  ASSERT_TRUE(std::filesystem::exists(dir.path() / "series.xdmf"));

  EXPECT_TRUE(read_series_info(file).complete);
  h5::Handle f = h5::open_file(file);
  EXPECT_EQ(h5::read_doubles(f.get(), "time", 3), times);
  EXPECT_EQ(h5::read_u64(f.get(), "step", 3), (std::vector<std::uint64_t>{20, 45, 70}));
  for (std::size_t k = 0; k < 3; ++k) {
    h5::Handle g = h5::open_group(f.get(), h5_frame_group(k));
    const std::size_t n = written[k].size();
    EXPECT_EQ(h5::read_vec3(g.get(), "position", n), written[k].position);
    EXPECT_EQ(h5::read_vec3(g.get(), "velocity", n), written[k].velocity);
    EXPECT_EQ(h5::read_vec3(g.get(), "omega", n), written[k].omega);
    EXPECT_EQ(h5::read_doubles(g.get(), "radius", n), written[k].radius);
    EXPECT_EQ(h5::read_u32(g.get(), "id", n), written[k].id);
    EXPECT_EQ(h5::read_u8(g.get(), "size_class", n), written[k].size_class);
    EXPECT_EQ(h5::read_double_attribute(g.get(), "time"), times[k]);
  }
  EXPECT_NE(written[0].position, written[2].position) << "frames must differ";

  const std::string x = read_text(dir.path() / "series.xdmf");
  EXPECT_NE(x.find("<Xdmf Version=\"3.0\""), std::string::npos);
  EXPECT_NE(x.find("CollectionType=\"Temporal\""), std::string::npos);
  const auto count = [&](const std::string& s) {
    std::size_t c = 0;
    for (auto at = x.find(s); at != std::string::npos; at = x.find(s, at + 1)) ++c;
    return c;
  };
  EXPECT_EQ(count("TopologyType=\"Polyvertex\""), 3u);
  EXPECT_EQ(count("GeometryType=\"XYZ\""), 3u);
  EXPECT_EQ(count("<Time Value="), 3u);
  EXPECT_EQ(count("<Attribute "), 15u);  // velocity, angular_velocity, radius, id, size_class
  // Every DataItem: "N 3" or "N", in series.h5, naming a dataset of that many values.
  const std::regex item(
      R"re(<DataItem Dimensions="(\d+)( 3)?"[^>]*>series\.h5:(/[^<]+)</DataItem>)re");
  std::size_t items = 0;
  for (auto it = std::sregex_iterator(x.begin(), x.end(), item); it != std::sregex_iterator();
       ++it, ++items) {
    const std::size_t n = std::stoul((*it)[1]) * ((*it)[2].matched ? 3 : 1);
    const std::string path = (*it)[3];
    EXPECT_TRUE(h5::exists(f.get(), path)) << path;
    EXPECT_EQ(h5::element_count(f.get(), path), n) << path;
  }
  EXPECT_EQ(items, 18u);  // geometry + 5 attributes, 3 frames
}

TEST(H5Series, UnfinishedSeriesKeepsItsFramesUnwritableOneLeavesNoFile) {
  TempDir dir("h5-series-bad");
  const auto sim = settled_simulation(output_scene(), 5);
  {
    H5Series series(dir.path() / "abandoned.h5");
    series.write_frame(sim->particles(), sim->time(), sim->steps());
  }  // destroyed without finish(): e.g. the run became unstable
  const SeriesInfo info = read_series_info(dir.path() / "abandoned.h5");
  EXPECT_EQ(info.frames, 1u);
  EXPECT_FALSE(info.complete) << "an unfinished series must not look complete";
  EXPECT_THROW(H5Series(dir.path() / "missing" / "s.h5"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "missing"));
}

TEST(H5Series, FullDiskStopsWithInputErrorAndLeavesNoFile) {
  TempDir dir("h5-series-full");
  const auto sim = settled_simulation(output_scene(), 5);
  {
    const FileSizeLimit limit(32 * 1024);  // a frame of 250 particles is about 25 kB
    ASSERT_TRUE(limit.ok());
    H5Series series(dir.path() / "s.h5");
    EXPECT_THROW(
        {
          for (int k = 0; k < 10; ++k) series.write_frame(sim->particles(), sim->time(), k);
          series.finish();
        },
        InputError);
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 0);
}

}  // namespace
}  // namespace drumlab::test
