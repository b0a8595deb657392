#pragma once
// The bookkeeping of a VTU/PVD time series in one directory: frame file names
// (STEM_NNNNNN.EXT, numbered from 0) and the .pvd collection of each stem, rewritten atomically
// after every frame so it always lists a valid series of the frames written so far. Without VTK:
// render/'s VtuSeriesWriter and drumlab-mpi's writer share it.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace drumlab::paraview {

struct PvdEntry {
  double time = 0.0;
  std::string file;  ///< relative to the .pvd
};

/// The text of a VTK "Collection" file (ParaView's .pvd).
std::string pvd_text(const std::vector<PvdEntry>& entries);

class PvdSeries {
 public:
  /// Creates `directory` if needed; throws InputError if it cannot.
  explicit PvdSeries(std::filesystem::path directory);

  /// The file name of `stem` in the frame being written (frames() is its number).
  std::string file_name(const std::string& stem, const char* ext) const;
  /// Ends the frame: adds each (stem, file) written for it at `time` to the stem's collection,
  /// rewrites those .pvd files, and counts the frame. Call it only once every file exists.
  void commit(const std::vector<std::pair<std::string, std::string>>& files, double time);

  const std::filesystem::path& directory() const { return dir_; }
  std::size_t frames() const { return frames_; }

 private:
  std::filesystem::path dir_;
  std::size_t frames_ = 0;
  std::vector<std::pair<std::string, std::vector<PvdEntry>>> series_;
};

}  // namespace drumlab::paraview
