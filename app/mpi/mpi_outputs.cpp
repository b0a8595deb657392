#include "app/mpi/mpi_outputs.hpp"

#include <optional>
#include <string>

#include <fmt/format.h>

#include "app/run/output_schedule.hpp"
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
  SeriesWriter(MpiDomain& domain, const std::string& file, double granule_age, bool gather,
               OutputTimes& times)
      : domain_(domain), granule_age_(granule_age), gather_(gather), times_(times) {
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
        write_series_frame(*series_, whole, granule_age_, bonds_);
      });
    } else {
      write_frame_mpi(*series_, domain_, sim, granule_age_);
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
  double granule_age_;
  bool gather_;
  OutputTimes& times_;
  std::optional<H5Series> series_;
  std::vector<Bond> bonds_;  ///< rank 0's scratch for a gathered frame of a scene with bonds
};

/// --agglomerates FILE.csv: the state gathered on rank 0, its agglomerates found there.
class AgglomerateWriter final : public FrameObserver {
 public:
  AgglomerateWriter(MpiDomain& domain, const std::string& file, double granule_age)
      : domain_(domain) {
    h5::on_root(domain_.comm().comm(), [&] { rows_.emplace(file, granule_age); });
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
  std::optional<cli::AgglomerateRows> rows_;  ///< rank 0's
};

}  // namespace

std::vector<std::unique_ptr<FrameObserver>> make_mpi_outputs(MpiDomain& domain,
                                                             const cli::RunOptions& opt,
                                                             bool gather, OutputTimes& times) {
  if (!opt.vtu_dir.empty()) {
    throw InputError(
        "--vtu: drumlab-mpi writes no VTU (it must not link VTK): write --h5 FILE and convert it "
        "with `drumlab convert FILE --vtu DIR`");
  }
  std::vector<std::unique_ptr<FrameObserver>> out;
  if (!opt.h5_file.empty()) {
    out.push_back(
        std::make_unique<SeriesWriter>(domain, opt.h5_file, opt.granule_age, gather, times));
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
  if (!opt.agglomerates.empty()) {  // last: it opens FILE.part at once
    cli::check_parent_directory(opt.agglomerates, "--agglomerates");
    out.push_back(std::make_unique<AgglomerateWriter>(domain, opt.agglomerates, opt.granule_age));
  }
  return out;
}

}  // namespace drumlab::mpi
