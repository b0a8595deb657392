#pragma once
// A compact HDF5 time series of the particles with an XDMF 3 sidecar that ParaView opens
// (Xdmf3ReaderT), streamed to disk frame by frame so memory stays bounded and a killed run keeps
// its frames. Layout:
//   /frame_NNNNNN/{position, velocity, omega (N x 3), radius (N), id (N, u32), size_class (N, u8)}
//                 with scalar attributes `time` and `step`;
//   /time, /step  one value per complete frame (growing 1D datasets);
//   root attribute `complete` = 1, written by finish() only.
// A scene with bonds (scene_has_bonds) adds to every frame mass (N), liquid_volume (N, the film;
// 0 without a film array), agglomerate_id (N, u32) and the bond graph
// /frame_NNNNNN/bonds/{id_a, id_b (u32, stable ids), volume, force, age}, with frame attributes
// `period_z`, `drum_omega` and `wall_bridge_liquid` (m^3 in bridges with the wall: what the
// agglomerate analysis needs to rerun afterwards).
// Each frame opens the file, appends, flushes (H5Fflush) and closes it (so HDF5's metadata cache
// never grows with the run, and a reader can open the file between frames), then the sidecar
// FILE.xdmf is rewritten atomically, listing the frames written so far (after every frame of the
// first kSidecarEveryFrame, then at most twice a second: its size grows with the frames). A run
// killed with SIGKILL leaves a file whose /time lists its complete frames, and a sidecar that
// opens them (all, or all but the last half second's of a long fast series); such a file has no
// `complete` attribute. A failed write (disk full) removes both files.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "engine/contact/bond.hpp"
#include "engine/io/h5_file.hpp"
#include "engine/io/series_frame.hpp"
#include "engine/particles.hpp"
#include "engine/spray/spray_liquid.hpp"

namespace drumlab {

/// A frame's bond graph as the series stores it: one row per bond, its ends as stable ids.
struct SeriesBondRows {
  std::vector<std::uint32_t> id_a, id_b;
  std::vector<double> volume, force, age;
  std::size_t size() const { return id_a.size(); }
  void push_back(std::uint32_t a, std::uint32_t b, const Bond& bond);
};
/// The rows of `bonds` (ends: storage slots of `p`), in their order.
SeriesBondRows series_bond_rows(const Particles& p, std::span<const Bond> bonds);

/// The bond graph and agglomerate labels of a frame (scenes with bonds only).
struct SeriesBondFrame {
  SeriesBondRows bonds;                           ///< this process's rows of the bond list
  std::span<const std::uint32_t> agglomerate_id;  ///< per particle, as the particles
  double period = 0.0;                            ///< z period of periodic ends, 0: none
  double drum_omega = 0.0;                        ///< rad/s
  double wall_liquid = 0.0;  ///< liquid in bridges with the wall, of all particles (m^3)
  /// Serial: all rows. Parallel: this rank's rows of the frame's bond list (increasing, the rows
  /// of `bonds` in their order), every rank passing the same scalars.
  h5::Rows bond_rows = h5::all_rows();
  SprayLiquid spray{};  ///< the spray's terms of the liquid accounting (frame attributes)
};

class H5Series {
 public:
  /// The sidecar is rewritten after each of the first kSidecarEveryFrame frames, then at most
  /// once per kSidecarInterval (wall time), and at finish().
  static constexpr std::size_t kSidecarEveryFrame = 200;
  static constexpr std::chrono::milliseconds kSidecarInterval{500};

  /// How the series reaches its file. Serial (the default): this process writes all of it.
  /// Parallel (engine/io/mpi/h5_series_mpi.hpp): every rank of a decomposed run opens the file
  /// through MPI-IO (`create`, `open`, `close`, collective) and writes the rows of its particles
  /// (`rows`, set before each frame by set_rows); `scalar` says who writes the appended /time
  /// and /step values; the `root` rank alone checks the path, writes the sidecar and removes the
  /// files after a failed write (which every rank meets alike).
  struct Access {
    std::function<h5::Handle(const std::filesystem::path&)> create, open;
    std::function<void(h5::Handle&, const std::filesystem::path&)> close;
    h5::Rows rows, scalar;
    bool root = true;
  };
  static Access serial_access();

  /// Checks that `file` can be written (throws InputError if not; on the root only); the file is
  /// created at the first frame.
  explicit H5Series(std::filesystem::path file, Access access = serial_access());
  /// The rows of the next frame's particles in a parallel series (see Access).
  void set_rows(h5::Rows rows);
  /// An unfinished series keeps its complete frames (no `complete` attribute).
  ~H5Series();
  H5Series(const H5Series&) = delete;
  H5Series& operator=(const H5Series&) = delete;

  /// Appends one frame, flushes it to disk and rewrites the sidecar. Throws InputError if it
  /// cannot be written (then the file and the sidecar are removed).
  void write_frame(const Particles& p, double time, std::uint64_t step,
                   const SeriesBondFrame* bonds = nullptr);
  /// Marks the series complete and closes the file.
  void finish();

  const std::filesystem::path& file() const { return file_; }
  std::filesystem::path xdmf_file() const;
  std::size_t frames() const { return times_.size(); }

 private:
  struct Impl;
  void open_for_writing();
  void close_after_writing();
  void write_sidecar() const;
  void discard() noexcept;
  std::filesystem::path file_;
  std::unique_ptr<Impl> impl_;
  std::vector<double> times_;
  std::string xdmf_grids_;  ///< the sidecar's grids of the frames so far (~2 kB a frame)
  std::chrono::steady_clock::time_point last_sidecar_{};
  bool finished_ = false;
};

/// Name of the group of frame k ("frame_000042").
std::string h5_frame_group(std::size_t k);

/// The XDMF 3 text describing the series: a temporal collection of Polyvertex grids whose XYZ
/// geometry and attributes are HyperSlab-free references "h5_name:/frame_k/dataset"; frames
/// with bonds (with_bonds[k], may be empty: none) also list agglomerate_id and liquid_volume.
std::string xdmf_for_series(const std::string& h5_name, const std::vector<double>& times,
                            const std::vector<std::size_t>& counts,
                            const std::vector<bool>& with_bonds = {});

/// Reads a series: the number of complete frames (the length of /time) and whether it was
/// finished. Throws InputError naming the file if it is not a series.
struct SeriesInfo {
  std::size_t frames = 0;
  bool complete = false;
  bool has_bonds = false;  ///< frames carry the bond graph
};
SeriesInfo read_series_info(const std::filesystem::path& file);
/// Frame k of the series, with its bond graph where the frame has one. Throws InputError naming
/// the file and frame if the frame is missing or inconsistent.
SeriesFrame read_series_frame(const std::filesystem::path& file, std::size_t k);

}  // namespace drumlab
