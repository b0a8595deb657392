#include "app/cli/output_observers.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "app/run/observable_rows.hpp"
#include "app/run/output_schedule.hpp"
#include "app/run/plain_vtu_series.hpp"
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
    print_vtu_written(writer_.frames(), writer_.directory());
  }

 private:
  render::VtuSeriesWriter writer_;
};
#else
/// --vtu without VTK: the same frames by the plain XML writer.
class PlainVtuObserver final : public FrameObserver {
 public:
  explicit PlainVtuObserver(const RunOptions& opt)
      : series_(opt.vtu_dir, opt.contacts_vtk, opt.granule.criterion,
                paraview::parse_view_frame(opt.vtu_frame(), "--frame")) {}
  void on_frame(const Simulation& sim, std::uint64_t) override { series_.write_frame(sim); }
  void on_finish(const Simulation&) override {
    print_vtu_written(series_.frames(), series_.directory());
  }

 private:
  PlainVtuSeries series_;
};
#endif

/// --observables FILE.csv: a row of drum observables per frame.
class ObservableObserver final : public FrameObserver {
 public:
  explicit ObservableObserver(const std::string& file) : rows_(file) {}
  void on_frame(const Simulation& sim, std::uint64_t) override { rows_.add(sim); }
  void on_finish(const Simulation&) override { rows_.finish(); }

 private:
  ObservableRows rows_;
};

class H5Observer final : public FrameObserver {
 public:
  H5Observer(const std::string& file, const GranuleCriterion& granule)
      : series_(file), granule_(granule) {}
  void on_frame(const Simulation& sim, std::uint64_t) override {
    write_series_frame(series_, sim, granule_, bonds_);
  }
  void on_finish(const Simulation&) override {
    series_.finish();
    print_series_written(series_.frames(), series_.file(), series_.xdmf_file());
  }

 private:
  H5Series series_;
  GranuleCriterion granule_;
  std::vector<Bond> bonds_;
};

/// --agglomerates FILE.csv: a row per frame, the chart FILE.png at the end.
class AgglomerateObserver final : public FrameObserver {
 public:
  AgglomerateObserver(const std::string& file, const GranuleCriterion& granule)
      : rows_(file, granule) {}
  void on_frame(const Simulation& sim, std::uint64_t) override { rows_.add(sim); }
  void on_finish(const Simulation&) override {
    rows_.finish();
#ifdef DRUMLAB_WITH_RENDER
    const AgglomerateTable& table = rows_.table();
    if (!table.rows().empty()) {
      render::write_agglomerate_chart(table.rows(), table.chart_file());
      fmt::print("agglomerate chart {}\n", table.chart_file().string());
    }
#endif
  }

 private:
  AgglomerateRows rows_;
};

}  // namespace

std::vector<std::unique_ptr<FrameObserver>> make_output_observers(const RunOptions& opt) {
  std::vector<std::unique_ptr<FrameObserver>> out;
  if (!opt.vtu_dir.empty()) {
#ifdef DRUMLAB_WITH_RENDER
    render::VtuSeriesOptions v;
    v.contacts = opt.contacts_vtk;
    v.grid = opt.grid_vtk;
    v.granule = opt.granule.criterion;
    v.frame = paraview::parse_view_frame(opt.vtu_frame(), "--frame");
    out.push_back(std::make_unique<VtuObserver>(opt.vtu_dir, v));
#else
    if (opt.grid_vtk) {
      throw InputError(
          "--grid-vtk: this build has no VTK (configure with DRUMLAB_BUILD_RENDER=ON)");
    }
    out.push_back(std::make_unique<PlainVtuObserver>(opt));
#endif
  }
  if (!opt.h5_file.empty()) {
    out.push_back(std::make_unique<H5Observer>(opt.h5_file, opt.granule.criterion));
  }
  if (!opt.checkpoint.empty()) {
    check_parent_directory(opt.checkpoint, "--checkpoint");
    const std::string file = opt.checkpoint;
    out.push_back(std::make_unique<CheckpointSchedule>(
        file, opt.checkpoint_every,
        [file](const Simulation& sim) { write_checkpoint(file, sim.state(), sim.scene().name); },
        true));
  }
  if (!opt.observables.empty()) {  // it opens FILE.part at once
    check_parent_directory(opt.observables, "--observables");
    out.push_back(std::make_unique<ObservableObserver>(opt.observables));
  }
  if (!opt.agglomerates.empty()) {  // last: it opens FILE.part at once
    check_parent_directory(opt.agglomerates, "--agglomerates");
    out.push_back(std::make_unique<AgglomerateObserver>(opt.agglomerates, opt.granule.criterion));
  }
  return out;
}

}  // namespace drumlab::cli
