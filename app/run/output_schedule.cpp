#include "app/run/output_schedule.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "engine/analysis/agglomerates.hpp"

namespace drumlab::cli {

std::uint64_t frame_every(const RunOptions& opt, std::uint64_t turn_steps, bool frames_taken) {
  if (opt.every > 0) return opt.every;
  if (opt.frames > 0) return std::max<std::uint64_t>(1, turn_steps / opt.frames);
  return frames_taken ? std::max<std::uint64_t>(1, turn_steps / 100) : 0;
}

void check_parent_directory(const std::string& file, const char* flag) {
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
    throw InputError(
        fmt::format("{} {}: directory {} does not exist", flag, file, parent.string()));
  }
}

CheckpointSchedule::CheckpointSchedule(std::string file, std::uint64_t every, Write write,
                                       bool report)
    : file_(std::move(file)), every_(every), write_(std::move(write)), report_(report) {}

void CheckpointSchedule::on_frame(const Simulation& sim, std::uint64_t frame) {
  // The start of the turn holds nothing new; without a schedule of its own (every_ 0) the
  // checkpoint still sees the run's frames, and waits for the end.
  if (frame == 0 || every_ == 0) return;
  write_(sim);
  ++written_;
  last_step_ = sim.steps();
}

void CheckpointSchedule::on_finish(const Simulation& sim) {
  if (written_ == 0 || last_step_ != sim.steps()) {
    write_(sim);
    ++written_;
  }
  if (report_) {
    fmt::print("checkpoint        {} (step {}, t = {:.6g} s)\n", file_, sim.steps(), sim.time());
  }
}

AgglomerateRows::AgglomerateRows(const std::string& file, const GranuleCriterion& granule)
    : table_(file), granule_(granule) {}

void AgglomerateRows::add(const Simulation& whole) {
  const AgglomerateInput in = agglomerate_input(whole, bonds_);
  table_.add(find_agglomerates(in, granule_options(whole.scene().drum.omega, granule_)).stats);
}

void AgglomerateRows::finish() {
  table_.finish();
  const auto& rows = table_.rows();
  if (rows.empty()) return;
  const AgglomerateStats& last = rows.back();
  fmt::print(
      "agglomerates      {} frames in {} ({}); last frame: {} of size >= 2, largest {}, d50 "
      "{:.3g} mm; largest plain component {:.1f} % of the bed\n",
      rows.size(), table_.file().string(), last.criterion, last.count, last.largest,
      1000.0 * last.d50, 100.0 * last.largest_plain_share);
}

void print_vtu_written(std::size_t frames, const std::filesystem::path& directory) {
  fmt::print("vtu               {} frames in {} (open particles.pvd in ParaView)\n", frames,
             directory.string());
}

void print_series_written(std::size_t frames, const std::filesystem::path& file,
                          const std::filesystem::path& xdmf) {
  fmt::print("h5                {} frames in {} (open {} in ParaView)\n", frames, file.string(),
             xdmf.string());
}

}  // namespace drumlab::cli
