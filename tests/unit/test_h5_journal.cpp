// The undo journal of a streamed series (engine/io/h5_journal.hpp): a writer killed at any of its
// writes to the disk while a frame goes out leaves a series that opens with exactly the frames
// before it, bit for bit; a reader that finds the journal of a live writer reads the series as
// its last complete frame left it and changes nothing; once the writer is dead, the next reader
// rolls the file back and removes the journal.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <vector>

#include "engine/io/h5_file.hpp"
#include "engine/io/h5_journal.hpp"
#include "engine/io/h5_series.hpp"
#include "tests/unit/cli_runner.hpp"
#include "tests/unit/output_test_scene.hpp"

namespace drumlab::test {
namespace {

constexpr int kKilled = 42;

/// Four frames of the turning drum, 25 steps apart.
std::vector<Particles> four_frames() {
  auto sim = settled_simulation(output_scene(), 20);
  std::vector<Particles> frames;
  for (int k = 0; k < 4; ++k) {
    frames.push_back(sim->particles());
    sim->advance(25);
  }
  return frames;
}

/// In a child process: writes frames 0 to `before` - 1 whole (frame k holds frames[k % 4]), then
/// frame `before` with `action` before the journal driver's n-th disk write of it, then exits 0.
/// Returns the child's wait status.
int write_in_child(const std::filesystem::path& file, const std::vector<Particles>& frames,
                   std::size_t before, long n, void (*action)(), bool wait_stopped = false) {
  const pid_t child = ::fork();
  if (child == 0) {
    try {
      H5Series series(file);
      for (std::size_t k = 0; k <= before; ++k) {
        if (k == before) h5::journal_testing::before_io(n, action);
        series.write_frame(frames[k % 4], 0.1 * static_cast<double>(k), 25 * k);
      }
      h5::journal_testing::before_io(-1, nullptr);
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, wait_stopped ? WUNTRACED : 0);
  if (wait_stopped && WIFSTOPPED(status)) return -child;
  return status;
}

void expect_frames(const std::filesystem::path& file, const std::vector<Particles>& frames,
                   std::size_t count, const std::string& where) {
  const SeriesInfo info = read_series_info(file);
  ASSERT_EQ(info.frames, count) << where;
  for (std::size_t k = 0; k < count; ++k) {
    const SeriesFrame f = read_series_frame(file, k);
    EXPECT_EQ(f.step, 25 * k) << where;
    EXPECT_EQ(f.position, frames[k % 4].position) << where << " frame " << k;
    EXPECT_EQ(f.velocity, frames[k % 4].velocity) << where << " frame " << k;
  }
}

// Frame 3 while the root group lists its links in the object header; frame 6, whose link turns
// that into dense storage (a fractal heap and a B-tree: HDF5 1.8's default beyond 8 links);
// frame 40, inside dense storage.
class H5JournalKill : public ::testing::TestWithParam<std::size_t> {};

TEST_P(H5JournalKill, WriterKilledAtAnyDiskWriteLeavesTheFramesBefore) {
  const std::size_t before = GetParam();
  TempDir dir("h5-journal");
  const auto frames = four_frames();
  const auto file = dir.path() / "s.h5";
  long n = 0;
  int unreadable_as_left = 0;  // kill points whose file HDF5 alone cannot open
  for (; n < 2000; ++n) {
    const int status = write_in_child(file, frames, before, n, [] { ::_exit(kKilled); });
    ASSERT_TRUE(WIFEXITED(status)) << n;
    if (WEXITSTATUS(status) == 0) break;
    ASSERT_EQ(WEXITSTATUS(status), kKilled) << n;
    const std::string where = "killed before disk write " + std::to_string(n);
    // Before its journal is in place (n = 0) the writer has changed nothing; after, it is left.
    EXPECT_EQ(std::filesystem::exists(h5::journal_path(file)), n > 0) << where;
    // What the kill left, opened by HDF5 without the journal (on a copy).
    const auto raw = dir.path() / "raw.h5";
    std::filesystem::copy_file(file, raw, std::filesystem::copy_options::overwrite_existing);
    h5::quiet();
    const hid_t f = H5Fopen(raw.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0 || H5Lexists(f, "time", H5P_DEFAULT) <= 0) ++unreadable_as_left;
    if (f >= 0) H5Fclose(f);
    expect_frames(file, frames, before, where);
    EXPECT_FALSE(std::filesystem::exists(h5::journal_path(file))) << where << ": rolled back";
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_LT(n, 2000) << "the frame never finished";
  EXPECT_GE(n, 4) << "a frame writes a journal, pages of the old file, new data, and commits";
  // Without the journal some of these files would not open: the test can tell (frame 3: 7 of
  // 26 kill points, frame 6: 19 of 37; at frame 40 none of the 28 happened to, measured
  // 2026-12-06; the rollback is checked at each all the same).
  if (before <= 6) {
    EXPECT_GT(unreadable_as_left, 0);
  }
  std::printf("frame %zu: %ld disk writes, %d of them left a file HDF5 alone cannot open\n", before,
              n, unreadable_as_left);
  expect_frames(file, frames, before + 1, "not killed");
  EXPECT_FALSE(std::filesystem::exists(h5::journal_path(file)));
}

INSTANTIATE_TEST_SUITE_P(Frames, H5JournalKill, ::testing::Values(3, 6, 40));

TEST(H5Journal, ReaderReadsThroughALiveWritersJournalThenRollsBackOnceItDies) {
  TempDir dir("h5-journal-live");
  const auto frames = four_frames();
  const auto file = dir.path() / "s.h5";
  // Stopped just before its commit: every page of frame 3 is written, the journal still held.
  long n = 0;
  while (WEXITSTATUS(write_in_child(file, frames, 3, n, [] { ::_exit(kKilled); })) == kKilled) ++n;
  ASSERT_GT(n, 1);
  const int stopped = write_in_child(
      file, frames, 3, n - 1, [] { ::raise(SIGSTOP); }, true);
  ASSERT_LT(stopped, 0) << "the writer did not stop";
  const pid_t writer = -stopped;
  const auto size_while_held = std::filesystem::file_size(file);
  expect_frames(file, frames, 3, "writer alive");
  EXPECT_TRUE(std::filesystem::exists(h5::journal_path(file)));
  EXPECT_EQ(std::filesystem::file_size(file), size_while_held) << "a reader changed the file";
  EXPECT_THROW(h5::open_file_rw(file), InputError) << "a second writer";
  ASSERT_EQ(::kill(writer, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(writer, &status, 0), writer);
  expect_frames(file, frames, 3, "writer dead");
  EXPECT_FALSE(std::filesystem::exists(h5::journal_path(file)));
  EXPECT_LT(std::filesystem::file_size(file), size_while_held) << "frame 3 cut off";
}

}  // namespace
}  // namespace drumlab::test
