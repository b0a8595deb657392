#include "app/cli/output_observers.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "engine/analysis/agglomerate_table.hpp"
#include "engine/analysis/agglomerates.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/h5_series.hpp"
#include "engine/io/h5_series_frame.hpp"
#ifdef DRUMLAB_WITH_RENDER
#include "render/agglomerate_chart.hpp"
#include "render/vtu_series_writer.hpp"
#endif

namespace drumlab::cli {
namespace {

#ifdef DRUMLAB_WITH_RENDER
class VtuObserver final : public FrameObserver {
 public:
  VtuObserver(const std::string& dir, render::VtuSeriesOptions options) : writer_(dir, options) {}
  void on_frame(const Simulation& sim, std::uint64_t) override { writer_.write_frame(sim); }
  void on_finish(const Simulation&) override {
    fmt::print("vtu               {} frames in {} (open particles.pvd in ParaView)\n",
               writer_.frames(), writer_.directory().string());
  }

 private:
  render::VtuSeriesWriter writer_;
};
#endif

class H5Observer final : public FrameObserver {
 public:
  H5Observer(const std::string& file, double granule_age)
      : series_(file), granule_age_(granule_age) {}
  void on_frame(const Simulation& sim, std::uint64_t) override {
    write_series_frame(series_, sim, granule_age_, bonds_);
  }
  void on_finish(const Simulation&) override {
    series_.finish();
    fmt::print("h5                {} frames in {} (open {} in ParaView)\n", series_.frames(),
               series_.file().string(), series_.xdmf_file().string());
  }

 private:
  H5Series series_;
  double granule_age_;
  std::vector<Bond> bonds_;
};

/// --agglomerates FILE.csv: a row per frame, the chart FILE.png at the end.
class AgglomerateObserver final : public FrameObserver {
 public:
  AgglomerateObserver(const std::string& file, double granule_age)
      : table_(file), granule_age_(granule_age) {}
  void on_frame(const Simulation& sim, std::uint64_t) override {
    const AgglomerateInput in = agglomerate_input(sim, bonds_);
    table_.add(find_agglomerates(in, granule_options(sim.scene().drum.omega, granule_age_)).stats);
  }
  void on_finish(const Simulation&) override {
    table_.finish();
    const auto& rows = table_.rows();
    if (!rows.empty()) {
      const AgglomerateStats& last = rows.back();
      fmt::print(
          "agglomerates      {} frames in {} ({}); last frame: {} of size >= 2, largest {}, "
          "d50 {:.3g} mm; largest plain component {:.1f} % of the bed\n",
          rows.size(), table_.file().string(), last.criterion, last.count, last.largest,
          1000.0 * last.d50, 100.0 * last.largest_plain_share);
    }
#ifdef DRUMLAB_WITH_RENDER
    if (!rows.empty()) {
      render::write_agglomerate_chart(rows, table_.chart_file());
      fmt::print("agglomerate chart {}\n", table_.chart_file().string());
    }
#endif
  }

 private:
  AgglomerateTable table_;
  double granule_age_;
  std::vector<Bond> bonds_;
};

class CheckpointObserver final : public FrameObserver {
 public:
  CheckpointObserver(std::string file, std::uint64_t every)
      : file_(std::move(file)), every_(every) {}
  void on_frame(const Simulation& sim, std::uint64_t) override {
    if (every_ == 0) return;
    if (next_ == 0) next_ = sim.steps() + every_;  // first frame: the turning phase starts
    if (sim.steps() < next_) return;
    write(sim);
    next_ = sim.steps() + every_;
  }
  void on_finish(const Simulation& sim) override {
    write(sim);
    fmt::print("checkpoint        {} (step {}, t = {:.6g} s)\n", file_, sim.steps(), sim.time());
  }

 private:
  void write(const Simulation& sim) const {
    write_checkpoint(file_, sim.state(), sim.scene().name);
  }
  std::string file_;
  std::uint64_t every_;
  std::uint64_t next_ = 0;
};

/// A file written only at the end must not fail after hours of running for want of a directory.
void check_parent_directory(const std::string& file, const char* flag) {
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
    throw InputError(
        fmt::format("{} {}: directory {} does not exist", flag, file, parent.string()));
  }
}

}  // namespace

std::vector<std::unique_ptr<FrameObserver>> make_output_observers(const RunOptions& opt) {
  std::vector<std::unique_ptr<FrameObserver>> out;
  if (!opt.vtu_dir.empty()) {
#ifdef DRUMLAB_WITH_RENDER
    render::VtuSeriesOptions v;
    v.contacts = opt.contacts_vtk;
    v.grid = opt.grid_vtk;
    v.granule_age = opt.granule_age;
    out.push_back(std::make_unique<VtuObserver>(opt.vtu_dir, v));
#else
    throw InputError("--vtu: this build has no VTK (configure with DRUMLAB_BUILD_RENDER=ON)");
#endif
  } else if (opt.contacts_vtk || opt.grid_vtk) {
    throw InputError("--contacts-vtk and --grid-vtk add to the VTU series: give --vtu DIR");
  }
  const auto same_file = [](const std::string& a, const std::string& b) {
    return std::filesystem::absolute(a).lexically_normal() ==
           std::filesystem::absolute(b).lexically_normal();
  };
  if (!opt.h5_file.empty() && !opt.checkpoint.empty() && same_file(opt.h5_file, opt.checkpoint)) {
    throw InputError(fmt::format("--h5 and --checkpoint both name {}", opt.h5_file));
  }
  if (!opt.h5_file.empty()) {
    out.push_back(std::make_unique<H5Observer>(opt.h5_file, opt.granule_age));
  }
  if (!opt.checkpoint.empty()) {
    check_parent_directory(opt.checkpoint, "--checkpoint");
    out.push_back(std::make_unique<CheckpointObserver>(opt.checkpoint, opt.checkpoint_every));
  } else if (opt.checkpoint_every > 0) {
    throw InputError("--checkpoint-every needs --checkpoint FILE");
  }
  if (!opt.agglomerates.empty()) {  // last: it opens FILE.part at once
    check_parent_directory(opt.agglomerates, "--agglomerates");
    out.push_back(std::make_unique<AgglomerateObserver>(opt.agglomerates, opt.granule_age));
  }
  return out;
}

}  // namespace drumlab::cli
