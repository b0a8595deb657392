#pragma once
// A compact HDF5 time series of the particles with an XDMF 3 sidecar that ParaView opens
// (Xdmf3ReaderT): one group per frame, /frame_NNNNNN/{position, velocity, omega (N x 3), radius
// (N), id (N, u32), size_class (N, u8)} with a scalar attribute `time`, plus /time (frames) and
// /step (frames) at the end. The file is assembled in memory (at most kMaxBytes) and written by
// finish() under FILE.tmp-PID, then renamed into place, followed by the sidecar FILE.xdmf (written
// the same way), so a failed run leaves no truncated file under either final name. (Memory rather
// than incremental disk writes: Debian's HDF5 1.10 crashes at exit after a failed disk write.)
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/particles.hpp"

namespace drumlab {

class H5Series {
 public:
  static constexpr std::size_t kMaxBytes = std::size_t{8} << 30;

  /// Checks that `file` can be written (throws InputError if not) and starts the series.
  explicit H5Series(std::filesystem::path file);
  ~H5Series();
  H5Series(const H5Series&) = delete;
  H5Series& operator=(const H5Series&) = delete;

  /// Appends one frame. Throws InputError if the series would exceed kMaxBytes.
  void write_frame(const Particles& p, double time, std::uint64_t step);
  /// Closes the file, writes the XDMF sidecar and renames both into place.
  void finish();

  const std::filesystem::path& file() const { return file_; }
  std::filesystem::path xdmf_file() const;
  std::size_t frames() const { return times_.size(); }

 private:
  struct Impl;
  std::filesystem::path file_;
  std::unique_ptr<Impl> impl_;
  std::vector<double> times_;
  std::vector<std::uint64_t> steps_;
  std::vector<std::size_t> counts_;
  bool finished_ = false;
};

/// Name of the group of frame k ("frame_000042").
std::string h5_frame_group(std::size_t k);

/// The XDMF 3 text describing the series: a temporal collection of Polyvertex grids whose XYZ
/// geometry and attributes are HyperSlab-free references "h5_name:/frame_k/dataset".
std::string xdmf_for_series(const std::string& h5_name, const std::vector<double>& times,
                            const std::vector<std::size_t>& counts);

}  // namespace drumlab
