#pragma once
// When a run's outputs are written, for `drumlab run` and `drumlab-mpi run` alike (each
// executable brings the writers of its own files: app/cli/output_observers.hpp with VTK,
// app/mpi/mpi_outputs.hpp with parallel HDF5): the frame writers (--h5, --vtu, --agglomerates)
// see frame 0 at the start of the turn and a frame every --every steps, each right after the
// stability check (RunSession::run_turn); the checkpoint is rewritten every --checkpoint-every
// turning steps on its own schedule and written at the end. Also the lines each writer prints
// at the end. VTK-free and HDF5-free.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/run/run_options.hpp"
#include "engine/analysis/agglomerate_table.hpp"
#include "engine/analysis/granule_criterion.hpp"
#include "engine/session/run_session.hpp"

namespace drumlab::cli {

/// Steps between the frames of the run: --every, else --frames spread over the turn, else 1/100
/// of the turn when some observer takes frames (`frames_taken`); 0: no frames.
std::uint64_t frame_every(const RunOptions& opt, std::uint64_t turn_steps, bool frames_taken);

/// A file written only at the end must not fail after hours of running for want of a directory:
/// throws InputError naming the flag if `file`'s directory does not exist.
void check_parent_directory(const std::string& file, const char* flag);

/// The checkpoint on its schedule: every `every` turning steps (0: never; not at the start) and
/// at the end (unless just written at that step), by `write`; `report` prints its line at the
/// end (rank 0 of a decomposed run).
class CheckpointSchedule final : public FrameObserver {
 public:
  using Write = std::function<void(const Simulation&)>;
  CheckpointSchedule(std::string file, std::uint64_t every, Write write, bool report);
  void on_frame(const Simulation& sim, std::uint64_t frame) override;
  void on_finish(const Simulation& sim) override;
  std::uint64_t every() const override { return every_; }
  std::uint64_t written() const { return written_; }

 private:
  std::string file_;
  std::uint64_t every_;
  Write write_;
  bool report_;
  std::uint64_t written_ = 0;
  std::uint64_t last_step_ = 0;
};

/// --agglomerates FILE.csv: a row per frame of the whole state (the serial simulation, or the
/// state a decomposed run gathered), the table closed at the end.
class AgglomerateRows {
 public:
  AgglomerateRows(const std::string& file, const GranuleCriterion& granule);
  void add(const Simulation& whole);
  /// Closes the table and prints its line.
  void finish();
  const AgglomerateTable& table() const { return table_; }

 private:
  AgglomerateTable table_;
  GranuleCriterion granule_;
  std::vector<Bond> bonds_;
};

/// The line of a VTU/PVD series at the end of the run.
void print_vtu_written(std::size_t frames, const std::filesystem::path& directory);

/// The line of an HDF5 series at the end of the run.
void print_series_written(std::size_t frames, const std::filesystem::path& file,
                          const std::filesystem::path& xdmf);

}  // namespace drumlab::cli
