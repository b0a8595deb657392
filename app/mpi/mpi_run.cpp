#include "app/mpi/mpi_run.hpp"

#include <sched.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "engine/analysis/agglomerates.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/h5_series_frame.hpp"
#include "engine/io/mpi/checkpoint_mpi.hpp"
#include "engine/io/mpi/h5_mpi.hpp"
#include "engine/io/mpi/h5_series_mpi.hpp"
#include "engine/parallel/ghost_layer.hpp"
#include "engine/parallel/mpi/mpi_domain.hpp"
#include "engine/threads.hpp"

namespace drumlab::mpi {

namespace {

/// Rank 0's string on every rank.
void broadcast(MPI_Comm comm, std::string& text) {
  int length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  text.resize(static_cast<std::size_t>(length));
  MPI_Bcast(text.data(), length, MPI_CHAR, 0, comm);
}

/// How the run starts: the scene as run and the plan on every rank; the whole state on rank 0
/// only, or every rank's share of a checkpoint.
struct Start {
  SceneConfig scene;
  SessionPlan plan;
  std::optional<SimulationState> full;
  std::string search_reason;  ///< how "auto" chose, if it did
  SimulationState share;      ///< rows [first, first + its size) of the checkpoint's total
  std::uint64_t first = 0, total = 0;
};

/// A restart with a search method named (not "auto", which times the candidates on the whole
/// state) is read in shares: every rank reads its rows of the checkpoint.
bool spread_restart(const SceneConfig& scene, const SessionOptions& o) {
  const std::string method = o.method.empty() ? scene.search_method : o.method;
  return !o.restart.empty() && method != "auto";
}

/// Every rank reads rows [N r / R, N (r + 1) / R) of the checkpoint; --method replaces its search
/// method, as RunSession does. Bad input met by any rank is thrown on every rank.
Start read_shares(MpiComm& comm, const SceneConfig& scene, const SessionOptions& o) {
  Start s;
  s.scene = scene_with_options(scene, o);
  std::string error;
  try {
    s.total = read_checkpoint_rows(o.restart, 0, 0).particles;
    const auto r = static_cast<std::uint64_t>(comm.rank());
    const auto n = static_cast<std::uint64_t>(comm.size());
    s.first = s.total * r / n;
    Checkpoint c = read_checkpoint_rows(o.restart, s.first, s.total * (r + 1) / n - s.first);
    if (!o.method.empty()) c.state.search_method = o.method;
    s.plan = session_plan(s.scene, o, c.state.dt, true);
    s.share = std::move(c.state);
  } catch (const InputError& e) {
    error = e.what();
  }
  error = comm.first_error(error);
  if (!error.empty()) throw InputError(error);
  return s;
}

/// Rank 0 alone fills the scene or reads the checkpoint (and resolves "auto"); the others get the
/// method and the plan from it and apply the same options to the scene. Bad input met by rank 0
/// is thrown on every rank.
Start start_run(MPI_Comm comm, int rank, const SceneConfig& scene, const SessionOptions& o) {
  Start s;
  std::string error;
  if (rank == 0) {
    try {
      RunSession session(scene, o);
      s.plan = session.plan();
      s.scene = session.scene();
      if (session.auto_choice()) s.search_reason = session.auto_choice()->reason;
      s.full = session.simulation().take_state();
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  broadcast(comm, error);
  if (!error.empty()) throw InputError(error);
  std::string method = s.scene.search_method;
  broadcast(comm, method);
  std::uint64_t steps[2] = {s.plan.settle_steps, s.plan.turn_steps};
  MPI_Bcast(steps, 2, MPI_UINT64_T, 0, comm);
  MPI_Bcast(&s.plan.settle_time, 1, MPI_DOUBLE, 0, comm);
  if (rank != 0) {
    s.scene = scene_with_options(scene, o);
    s.scene.search_method = method;
    s.plan.settle_steps = steps[0];
    s.plan.turn_steps = steps[1];
  }
  return s;
}

MpiDomainOptions domain_options(const SceneConfig& scene, const MpiRunOptions& o) {
  MpiDomainOptions d;
  const double skin = scene.performance.verlet_skin * scene.min_radius();
  d.skin = skin;
  d.reach = ghost_reach(scene.max_radius(), ContactModel(scene).max_pair_range(), skin);
  if (scene.drum.ends == DrumEnds::periodic) d.period_z = scene.drum.depth;
  d.domain = drum_domain(scene.drum.diameter, scene.drum.depth);
  d.rebalance_every = o.rebalance_every;
  d.balance = o.balance;
  d.balance_threshold = o.balance_threshold;
  return d;
}

/// Checkpoints and the series: written by every rank into one file (parallel HDF5, the serial
/// layout), or with --gather-output gathered on rank 0 and written there by the serial writer;
/// each write timed on this rank.
struct Output {
  const MpiRunOptions& o;
  bool gather_series = false;
  std::optional<H5Series> series;
  std::vector<Bond> bonds;  ///< rank 0's scratch for a gathered frame of a scene with bonds
  std::uint64_t checkpoints = 0, frames = 0;
  double checkpoint_seconds = 0.0, frame_seconds = 0.0;
};

void write_checkpoint_now(MpiDomain& domain, const Simulation& sim, Output& out) {
  const double t0 = MPI_Wtime();
  if (out.o.gather_output) {
    const auto state = domain.gather(sim);
    h5::on_root(domain.comm().comm(),
                [&] { write_checkpoint(out.o.checkpoint, *state, sim.scene().name); });
  } else {
    write_checkpoint_mpi(domain.comm(), sim, domain.slots(), out.o.checkpoint, sim.scene().name);
  }
  out.checkpoint_seconds += MPI_Wtime() - t0;
  ++out.checkpoints;
}

/// One frame of the series, as `drumlab run --h5` takes it: only of a state that has just passed
/// the stability check (collective).
void write_series_frame(MpiDomain& domain, Simulation& sim, Output& out) {
  sim.check_stability();
  const double t0 = MPI_Wtime();
  if (out.gather_series) {
    std::optional<SimulationState> state = domain.gather(sim);
    h5::on_root(domain.comm().comm(), [&] {
      const Simulation whole(sim.scene(), std::move(*state));  // the serial run at this step
      write_series_frame(*out.series, whole, out.o.granule_age, out.bonds);
    });
  } else {
    write_frame_mpi(*out.series, domain, sim, out.o.granule_age);
  }
  out.frame_seconds += MPI_Wtime() - t0;
  ++out.frames;
}

/// The series (every rank's, or rank 0's with --gather-output), its path checked now.
void open_series(MpiComm& comm, Output& out) {
  const MpiRunOptions& o = out.o;
  if (o.h5.empty()) return;
  if (out.gather_series) {
    h5::on_root(comm.comm(), [&] { out.series.emplace(o.h5); });
  } else {
    out.series.emplace(o.h5, mpi_series_access(comm, o.h5));
  }
}

/// The final checkpoint and the series' end.
void finish_output(MpiDomain& domain, const Simulation& sim, Output& out) {
  if (!out.o.checkpoint.empty()) write_checkpoint_now(domain, sim, out);
  if (out.o.h5.empty()) return;
  if (out.gather_series) {
    h5::on_root(domain.comm().comm(), [&] { out.series->finish(); });
  } else {
    out.series->finish();
  }
}

/// The turn: `steps` steps with the scheduled series frames (frame 0 first) and checkpoints.
void turn_drum(MpiDomain& domain, Simulation& sim, std::uint64_t steps, Output& out) {
  const MpiRunOptions& o = out.o;
  std::uint64_t every = 0;
  if (!o.h5.empty()) {
    every = o.every > 0 ? o.every : std::max<std::uint64_t>(1, steps / 100);
    write_series_frame(domain, sim, out);
  }
  std::uint64_t done = 0;
  while (done < steps) {
    std::uint64_t k = steps - done;
    if (o.checkpoint_every > 0) k = std::min(k, o.checkpoint_every - done % o.checkpoint_every);
    if (every > 0) k = std::min(k, every - done % every);
    sim.advance(k);
    done += k;
    if (every > 0 && done % every == 0) write_series_frame(domain, sim, out);
    if (!o.checkpoint.empty() && o.checkpoint_every > 0 && done % o.checkpoint_every == 0 &&
        done < steps) {
      write_checkpoint_now(domain, sim, out);
    }
  }
}

/// The cores this process may run on (its CPU affinity); 0 if unknown.
int allowed_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  return sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 0;
}

/// Rank 0 warns (one line on stderr) when a rank may run on fewer cores than it has threads:
/// mpirun binds each rank to one core by default, and the threads then share it (a run of
/// `--threads 2` as slow as one thread, or slower). Collective.
void warn_if_threads_share_cores(MPI_Comm comm, int rank, int threads) {
  const int mine = allowed_cores();
  int least = mine > 0 ? mine : std::numeric_limits<int>::max();
  MPI_Allreduce(MPI_IN_PLACE, &least, 1, MPI_INT, MPI_MIN, comm);
  if (rank == 0 && threads > least) {
    fmt::print(stderr,
               "drumlab-mpi: warning: a rank may run on {} core(s) but has {} threads, which "
               "share them (mpirun binds each rank to one core: add --bind-to none, or --map-by "
               "slot:PE={})\n",
               least, threads, threads);
  }
}

}  // namespace

MpiRunSummary run_mpi(MPI_Comm comm, const MpiRunOptions& o) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  set_thread_count(o.threads);
  warn_if_threads_share_cores(comm, rank, o.threads);
  SceneConfig scene = load_dynamic_scene(o.session.scene_file);
  if (!o.h5.empty() && !o.checkpoint.empty() &&
      std::filesystem::weakly_canonical(o.h5) == std::filesystem::weakly_canonical(o.checkpoint)) {
    throw InputError(fmt::format("--h5 and --checkpoint both name {}", o.h5));
  }
  Output out{o, o.gather_output, {}, {}};
  MpiComm io_comm(comm);
  open_series(io_comm, out);  // checked before the fill, written from the turn
  MpiRunSummary s;
  const bool shares = spread_restart(scene, o.session);
  Start start =
      shares ? read_shares(io_comm, scene, o.session) : start_run(comm, rank, scene, o.session);
  s.search_reason = std::move(start.search_reason);
  const SessionPlan plan = start.plan;
  const SceneConfig& run_scene = start.scene;
  MpiDomain domain(comm, domain_options(run_scene, o));
  std::unique_ptr<Simulation> sim =
      shares ? domain.distribute_shares(run_scene, std::move(start.share), start.first, start.total)
             : domain.distribute(run_scene, std::move(start.full));
  s.particles = domain.particles();
  MPI_Barrier(comm);
  const double t0 = MPI_Wtime();
  const double comm0 = domain.comm_seconds();  // the distribution is not part of the stepping
  if (plan.settle_steps > 0) {
    sim->set_drum_omega(0.0);
    sim->advance(plan.settle_steps);
    sim->set_drum_omega(run_scene.drum.omega);
  }
  const double t1 = MPI_Wtime();
  turn_drum(domain, *sim, plan.turn_steps, out);
  const double t2 = MPI_Wtime();
  const double comm2 = domain.comm_seconds();
  finish_output(domain, *sim, out);
  const MpiBalance b = domain.balance(*sim);
  const double share = (t2 - t0) > 0.0 ? (comm2 - comm0) / (t2 - t0) : 0.0;
  s.scene = run_scene.name;
  s.method = run_scene.search_method;
  s.ranks = ranks;
  s.threads = o.threads;
  s.settle_steps = plan.settle_steps;
  s.turn_steps = plan.turn_steps;
  s.seconds = t2 - t0;
  s.turn_seconds = t2 - t1;
  s.owned_min = b.owned_min;
  s.owned_max = b.owned_max;
  s.owned_mean = b.owned_mean;
  s.comm_share_max = domain.max(share);
  s.comm_share_mean = domain.sum(share) / ranks;
  s.exchanges = b.exchanges;
  s.exchange_seconds = domain.max(b.exchange_seconds);
  s.recut_seconds = domain.max(b.recut_seconds);
  const StepTimers& tm = sim->timers();
  for (auto [mine, mean] : {std::pair{tm.search, &s.split.search},
                            {tm.forces, &s.split.forces},
                            {tm.walls, &s.split.walls},
                            {tm.integration, &s.split.integration},
                            {tm.reorder, &s.split.reorder}}) {
    *mean = domain.sum(mine) / ranks;
  }
  s.rebalances = b.rebalances;
  s.balance = o.balance;
  s.rebalance_every = o.rebalance_every;
  s.balance_threshold = o.balance_threshold;
  s.first_imbalance = b.first_imbalance;
  s.last_imbalance = b.last_imbalance;
  s.ghosts_new = b.ghosts_new;
  s.ghosts_kept = b.ghosts_kept;
  s.wet = scene.liquid.enabled && scene.liquid.migration;
  s.bridge_events = b.bridge_events;
  s.checkpoints = out.checkpoints;
  s.frames = out.frames;
  s.checkpoint_seconds = domain.max(out.checkpoint_seconds);
  s.frame_seconds = domain.max(out.frame_seconds);
  return s;
}

}  // namespace drumlab::mpi
