#include "app/mpi/mpi_outputs.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "app/run/observable_rows.hpp"
#include "app/run/output_schedule.hpp"
#include "app/run/plain_vtu_series.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/h5_series_frame.hpp"
#include "engine/io/mpi/checkpoint_mpi.hpp"
#include "engine/io/mpi/h5_mpi.hpp"
#include "engine/io/mpi/h5_series_mpi.hpp"

namespace drumlab::mpi {
namespace {

/// Adds the seconds since construction to `sum` when it goes (every rank times its own part).
class Timed {
 public:
  explicit Timed(double& sum) : sum_(sum), t0_(MPI_Wtime()) {}
  ~Timed() { sum_ += MPI_Wtime() - t0_; }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;

 private:
  double& sum_;
  double t0_;
};

/// --h5 FILE: every rank writes its particles' rows of each frame, or rank 0 the gathered state.
class SeriesWriter final : public FrameObserver {
 public:
  SeriesWriter(MpiDomain& domain, const std::string& file, const GranuleCriterion& granule,
               bool gather, OutputTimes& times)
      : domain_(domain), granule_(granule), gather_(gather), times_(times) {
    if (gather_) {
      h5::on_root(root(), [&] { series_.emplace(file); });
    } else {
      series_.emplace(file, mpi_series_access(domain_.comm(), file));
    }
  }
  void on_frame(const Simulation& sim, std::uint64_t) override {
    const Timed t(times_.frame_seconds);
    if (gather_) {
      std::optional<SimulationState> state = domain_.gather(sim);
      h5::on_root(root(), [&] {
        const Simulation whole(sim.scene(), std::move(*state));  // the serial run at this step
        write_series_frame(*series_, whole, granule_, bonds_);
      });
    } else {
      write_frame_mpi(*series_, domain_, sim, granule_);
    }
    ++times_.frames;
  }
  void on_finish(const Simulation&) override {
    if (gather_) {
      h5::on_root(root(), [&] { series_->finish(); });
    } else {
      series_->finish();
    }
    if (domain_.comm().rank() == 0) {
      cli::print_series_written(series_->frames(), series_->file(), series_->xdmf_file());
    }
  }

 private:
  MPI_Comm root() { return domain_.comm().comm(); }
  MpiDomain& domain_;
  GranuleCriterion granule_;
  bool gather_;
  OutputTimes& times_;
  std::optional<H5Series> series_;
  std::vector<Bond> bonds_;  ///< rank 0's scratch for a gathered frame of a scene with bonds
};

/// --observables FILE.csv: the state gathered on rank 0, its observables measured there.
class ObservableWriter final : public FrameObserver {
 public:
  ObservableWriter(MpiDomain& domain, const std::string& file) : domain_(domain) {
    h5::on_root(domain_.comm().comm(), [&] { rows_.emplace(file); });
  }
  void on_frame(const Simulation& sim, std::uint64_t) override {
    std::optional<SimulationState> state = domain_.gather(sim);
    h5::on_root(domain_.comm().comm(),
                [&] { rows_->add(Simulation(sim.scene(), std::move(*state))); });
  }
  void on_finish(const Simulation&) override {
    h5::on_root(domain_.comm().comm(), [&] { rows_->finish(); });
  }

 private:
  MpiDomain& domain_;
  std::optional<cli::ObservableRows> rows_;  ///< rank 0's
};

/// The table's chart FILE.png, drawn as `drumlab run` draws it, by the `drumlab` executable beside
/// this one (`drumlab analyze FILE.csv`): the chart needs VTK, which an MPI executable does not
/// link. Without that executable, a line says how to draw it; if it fails, InputError.
void draw_chart(const std::filesystem::path& table) {
  std::error_code ec;
  const auto drumlab =
      std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() / "drumlab";
  if (ec || ::access(drumlab.c_str(), X_OK) != 0) {
    fmt::print(
        "agglomerate chart not drawn: no drumlab beside drumlab-mpi; "
        "`drumlab analyze {}` draws it\n",
        table.string());
    return;
  }
  std::fflush(stdout);
  const std::string path = drumlab.string(), command = "analyze", file = table.string();
  char* argv[] = {const_cast<char*>(path.c_str()), const_cast<char*>(command.c_str()),
                  const_cast<char*>(file.c_str()), nullptr};
  pid_t child = 0;
  int status = 0;
  if (::posix_spawn(&child, path.c_str(), nullptr, nullptr, argv, environ) != 0 ||
      ::waitpid(child, &status, 0) != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw InputError(
        fmt::format("{}: its chart was not drawn (`{} analyze {}` failed)", file, path, file));
  }
}

/// --agglomerates FILE.csv: the state gathered on rank 0, its agglomerates found there.
class AgglomerateWriter final : public FrameObserver {
 public:
  AgglomerateWriter(MpiDomain& domain, const std::string& file, const GranuleCriterion& granule)
      : domain_(domain) {
    h5::on_root(domain_.comm().comm(), [&] { rows_.emplace(file, granule); });
  }
  void on_frame(const Simulation& sim, std::uint64_t) override {
    std::optional<SimulationState> state = domain_.gather(sim);
    h5::on_root(domain_.comm().comm(),
                [&] { rows_->add(Simulation(sim.scene(), std::move(*state))); });
  }
  void on_finish(const Simulation&) override {
    h5::on_root(domain_.comm().comm(), [&] {
      rows_->finish();
      draw_chart(rows_->table().file());
    });
  }

 private:
  MpiDomain& domain_;
  std::optional<cli::AgglomerateRows> rows_;  ///< rank 0's
};

/// --vtu DIR: the state gathered on rank 0 and written there as the serial run writes it (an MPI
/// executable links no VTK: app/run/plain_vtu_series.hpp).
class VtuWriter final : public FrameObserver {
 public:
  VtuWriter(MpiDomain& domain, const cli::RunOptions& opt, OutputTimes& times)
      : domain_(domain), times_(times) {
    h5::on_root(root(), [&] {
      series_.emplace(opt.vtu_dir, opt.contacts_vtk, opt.granule.criterion,
                      paraview::parse_view_frame(opt.vtu_frame(), "--frame"));
    });
  }
  void on_frame(const Simulation& sim, std::uint64_t) override {
    const Timed t(times_.frame_seconds);
    std::optional<SimulationState> state = domain_.gather(sim);
    h5::on_root(root(), [&] {
      series_->write_frame(Simulation(sim.scene(), std::move(*state)));  // the serial run's state
    });
  }
  void on_finish(const Simulation&) override {
    if (series_) cli::print_vtu_written(series_->frames(), series_->directory());
  }

 private:
  MPI_Comm root() { return domain_.comm().comm(); }
  MpiDomain& domain_;
  OutputTimes& times_;
  std::optional<cli::PlainVtuSeries> series_;  ///< rank 0's
};

}  // namespace

std::vector<std::unique_ptr<FrameObserver>> make_mpi_outputs(MpiDomain& domain,
                                                             const cli::RunOptions& opt,
                                                             bool gather, OutputTimes& times) {
  if (opt.grid_vtk) {
    throw InputError(
        "--grid-vtk: each rank searches its own box, so a decomposed run has no one grid to "
        "write; `drumlab run --vtu DIR --grid-vtk` writes the serial run's");
  }
  if (!opt.h5_file.empty() && !gather && opt.granule.criterion.method == GranuleMethod::community) {
    throw InputError(
        "--granule-criterion community: the ranks write the --h5 series where the particles are, "
        "and communities need the whole bond network; add --gather-output, or run `drumlab "
        "analyze SERIES.h5 --granule-criterion community` on the series");
  }
  std::vector<std::unique_ptr<FrameObserver>> out;
  if (!opt.vtu_dir.empty()) out.push_back(std::make_unique<VtuWriter>(domain, opt, times));
  if (!opt.h5_file.empty()) {
    out.push_back(
        std::make_unique<SeriesWriter>(domain, opt.h5_file, opt.granule.criterion, gather, times));
  }
  if (!opt.checkpoint.empty()) {
    cli::check_parent_directory(opt.checkpoint, "--checkpoint");
    const std::string file = opt.checkpoint;
    auto write = [&domain, &times, gather, file](const Simulation& sim) {
      const Timed t(times.checkpoint_seconds);
      if (gather) {
        const auto state = domain.gather(sim);
        h5::on_root(domain.comm().comm(),
                    [&] { write_checkpoint(file, *state, sim.scene().name); });
      } else {
        write_checkpoint_mpi(domain.comm(), sim, domain.slots(), file, sim.scene().name);
      }
      ++times.checkpoints;
    };
    out.push_back(std::make_unique<cli::CheckpointSchedule>(file, opt.checkpoint_every, write,
                                                            domain.comm().rank() == 0));
  }
  if (!opt.observables.empty()) {  // it opens FILE.part at once
    cli::check_parent_directory(opt.observables, "--observables");
    out.push_back(std::make_unique<ObservableWriter>(domain, opt.observables));
  }
  if (!opt.agglomerates.empty()) {  // last: it opens FILE.part at once
    cli::check_parent_directory(opt.agglomerates, "--agglomerates");
    out.push_back(
        std::make_unique<AgglomerateWriter>(domain, opt.agglomerates, opt.granule.criterion));
  }
  return out;
}

}  // namespace drumlab::mpi
