// Output that cannot be written stops with a clear error and leaves no file under the final name;
// without ffmpeg the movie falls back to Ogg/Theora.
#include <filesystem>
#include <fstream>
#include <string_view>

#include <gtest/gtest.h>

#include "engine/types.hpp"
#include "render/frame_writer.hpp"
#include "render/movie_writer.hpp"
#include "tests/unit/cli_runner.hpp"

namespace drumlab {
namespace {

namespace fs = std::filesystem;

render::Image gradient(int w, int h) {
  render::Image img;
  img.width = w;
  img.height = h;
  img.rgb.resize(3 * static_cast<std::size_t>(w) * h);
  for (std::size_t k = 0; k < img.rgb.size(); ++k) img.rgb[k] = static_cast<std::uint8_t>(k % 251);
  return img;
}

TEST(OutputErrors, PngIntoAMissingDirectoryIsAnInputErrorAndLeavesNothing) {
  test::TempDir dir("png-missing");
  const fs::path file = dir.path() / "no-such-dir" / "frame.png";
  EXPECT_THROW(render::write_png(gradient(8, 8), file), InputError);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_FALSE(fs::exists(file.parent_path()));
}

TEST(OutputErrors, PngIsWrittenCompletelyAndOnlyUnderItsName) {
  test::TempDir dir("png-ok");
  const fs::path file = dir.path() / "frame.png";
  render::write_png(gradient(16, 9), file);
  ASSERT_TRUE(fs::exists(file));
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string_view(magic + 1, 3), "PNG");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 1);
}

TEST(OutputErrors, FrameDirectoryThatIsAFileIsAnInputError) {
  test::TempDir dir("frames-file");
  const fs::path blocker = dir.write("blocker", "x");
  EXPECT_THROW(render::FrameWriter(blocker / "frames"), InputError);
}

TEST(OutputErrors, MovieWithoutFfmpegFallsBackToTheora) {
  test::TempDir dir("ogv");
  render::FrameWriter frames(dir.path() / "frames");
  for (std::uint64_t f = 0; f < 6; ++f) frames.write(gradient(64, 48), f);
  render::MovieOptions opt;
  opt.frames_dir = frames.directory();
  opt.frames = 6;
  opt.ffmpeg = "drumlab-no-such-ffmpeg";
  const fs::path written = render::write_movie(opt, dir.path() / "movie.mp4");
  EXPECT_EQ(written, dir.path() / "movie.ogv");
  ASSERT_TRUE(fs::exists(written));
  EXPECT_GT(fs::file_size(written), 100u);
  EXPECT_FALSE(fs::exists(dir.path() / "movie.mp4"));
}

TEST(OutputErrors, MovieIntoAMissingDirectoryLeavesNothing) {
  test::TempDir dir("movie-missing");
  render::FrameWriter frames(dir.path() / "frames");
  frames.write(gradient(64, 48), 0);
  render::MovieOptions opt;
  opt.frames_dir = frames.directory();
  opt.frames = 1;
  EXPECT_THROW(render::write_movie(opt, dir.path() / "nope" / "m.mp4"), InputError);
  EXPECT_FALSE(fs::exists(dir.path() / "nope"));
}

TEST(RenderCli, TeachIntoAMissingDirectoryExitsWithCode2AndWritesNothing) {
  test::TempDir dir("teach-bad");
  const fs::path out = dir.path() / "missing" / "teach.png";
  const test::CliResult r = test::run_cli("teach --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(RenderCli, RenderWithAFileAsOutputDirectoryExitsWithCode2) {
  test::TempDir dir("render-bad");
  const fs::path blocker = dir.write("blocker", "x");
  const test::CliResult r = test::run_cli("render " + std::string(DRUMLAB_SCENES_DIR) +
                                          "/teach_stencil.toml --steps 5 --settle-time 0 --out " +
                                          (blocker / "frames").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

TEST(RenderCli, GridWithBruteForceIsRefusedBeforeSimulating) {
  test::TempDir dir("render-brute");
  const test::CliResult r =
      test::run_cli("render " + std::string(DRUMLAB_SCENES_DIR) +
                    "/teach_stencil.toml --method brute --grid --out " + dir.path().string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no cells"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("plan"), std::string::npos) << "refused before the run starts";
}

TEST(RenderCli, RendersFramesAndAMovieAndTeachPrintsFivePanels) {
  test::TempDir dir("render-ok");
  const test::CliResult r = test::run_cli(
      "render " + std::string(DRUMLAB_SCENES_DIR) +
      "/teach_stencil.toml --steps 40 --settle-time 0 --every 20 --size 320x240 --grid --focus "
      "auto --color-by coordination --out " +
      (dir.path() / "frames").string() + " --movie " + (dir.path() / "m.mp4").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"frame_00000.png", "frame_00001.png", "frame_00002.png"}) {
    EXPECT_TRUE(fs::exists(dir.path() / "frames" / f)) << f;
  }
  const bool movie = fs::exists(dir.path() / "m.mp4") || fs::exists(dir.path() / "m.ogv");
  EXPECT_TRUE(movie) << r.output;

  const test::CliResult t = test::run_cli("teach --out " + (dir.path() / "teach.png").string());
  ASSERT_EQ(t.exit_code, 0) << t.output;
  EXPECT_TRUE(fs::exists(dir.path() / "teach.png"));
  std::size_t lines = 0;
  for (std::size_t k = t.output.find("cells visited"); k != std::string::npos;
       k = t.output.find("cells visited", k + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 5u) << t.output;
}

// The render library says what is wrong in its own terms; the CLI names the flag in front.
TEST(RenderCli, LibraryErrorsGetTheFlagFromTheCli) {
  test::TempDir dir("render-flags");
  const std::string common = "render " + std::string(DRUMLAB_SCENES_DIR) +
                             "/teach_stencil.toml --steps 1 --settle-time 0 --size 64x64 --out " +
                             (dir.path() / "frames").string();
  const test::CliResult colour = test::run_cli(common + " --color-by hue");
  EXPECT_EQ(colour.exit_code, 2) << colour.output;
  EXPECT_NE(colour.output.find("--color-by: unknown colour mode 'hue'"), std::string::npos)
      << colour.output;
  const test::CliResult focus = test::run_cli(common + " --focus 999999");
  EXPECT_EQ(focus.exit_code, 2) << focus.output;
  EXPECT_NE(focus.output.find("--focus: focus particle 999999 does not exist (N = "),
            std::string::npos)
      << focus.output;
}

}  // namespace
}  // namespace drumlab
