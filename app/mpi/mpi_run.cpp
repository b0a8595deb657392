#include "app/mpi/mpi_run.hpp"

#include <sched.h>

#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "app/mpi/mpi_outputs.hpp"
#include "app/mpi/mpi_report.hpp"
#include "app/run/output_schedule.hpp"
#include "app/run/run_report.hpp"
#include "engine/contact/contact_model.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/restart_check.hpp"
#include "engine/parallel/ghost_layer.hpp"
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

/// How the run starts: the scene as run on every rank; the whole state on rank 0 only, or every
/// rank's share of a checkpoint; what rank 0's session chose and read (for its lines).
struct Start {
  SceneConfig scene;
  std::optional<SimulationState> full;
  SimulationState share;  ///< rows [first, first + its size) of the checkpoint's total
  std::uint64_t first = 0, total = 0;
  std::optional<SearchChoice> auto_choice;
  std::optional<RestartInfo> restart;
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
  comm.agree([&] {
    s.total = read_checkpoint_rows(o.restart, 0, 0).particles;
    check_restart_count(s.scene, s.total, o.restart);
    const auto r = static_cast<std::uint64_t>(comm.rank());
    const auto n = static_cast<std::uint64_t>(comm.size());
    s.first = s.total * r / n;
    Checkpoint c = read_checkpoint_rows(o.restart, s.first, s.total * (r + 1) / n - s.first);
    if (!o.method.empty()) c.state.search_method = o.method;
    s.restart = RestartInfo{o.restart, c.scene_name, o.dt_factor > 0.0};
    s.share = std::move(c.state);
  });
  return s;
}

/// Rank 0 alone fills the scene or reads the checkpoint (and resolves "auto"); the others get the
/// method from it and apply the same options to the scene. Bad input met by rank 0 is thrown on
/// every rank.
Start start_run(MPI_Comm comm, int rank, const SceneConfig& scene, const SessionOptions& o) {
  Start s;
  std::string error;
  if (rank == 0 && !scene.sprays.empty()) {
    error =
        "[[spray]]: not on drumlab-mpi yet (the droplets are not decomposed); run the scene "
        "with drumlab";
  } else if (rank == 0) {
    try {
      RunSession session(scene, o);
      s.scene = session.scene();
      s.auto_choice = session.auto_choice();
      s.restart = session.restart();
      s.full = session.simulation().take_state();
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  broadcast(comm, error);
  if (!error.empty()) throw InputError(error);
  std::string method = s.scene.search_method;
  broadcast(comm, method);
  if (rank != 0) {
    s.scene = scene_with_options(scene, o);
    s.scene.search_method = method;
    if (!o.restart.empty()) s.restart = RestartInfo{o.restart, {}, false};  // no settling
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

/// The decomposition's numbers of the run, over all ranks. Collective.
MpiRunSummary decomposition_summary(MpiDomain& domain, const Simulation& sim,
                                    const MpiRunOptions& o, double comm_share,
                                    const OutputTimes& out) {
  MpiRunSummary s;
  s.ranks = domain.comm().size();
  s.threads = o.run.threads;
  s.balance = domain.balance(sim);
  s.comm_share_max = domain.max(comm_share);
  s.comm_share_mean = domain.sum(comm_share) / s.ranks;
  s.exchange_seconds = domain.max(s.balance.exchange_seconds);
  s.recut_seconds = domain.max(s.balance.recut_seconds);
  s.balance_by = o.balance;
  s.rebalance_every = o.rebalance_every;
  s.balance_threshold = o.balance_threshold;
  s.wet = sim.scene().liquid.enabled && sim.scene().liquid.migration;
  s.output = out;
  s.output.checkpoint_seconds = domain.max(out.checkpoint_seconds);
  s.output.frame_seconds = domain.max(out.frame_seconds);
  return s;
}

}  // namespace

void run_mpi(MPI_Comm comm, const MpiRunOptions& o) {
  const cli::RunOptions& opt = o.run;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  set_thread_count(opt.threads);
  warn_if_threads_share_cores(comm, rank, opt.threads);
  MpiComm io_comm(comm);
  SceneConfig scene;  // every rank reads the file: one that some rank cannot read stops all
  io_comm.agree([&] { scene = load_dynamic_scene(opt.scene); });
  cli::check_run_options(opt);
  cli::check_run_options_for(opt, scene);
  const SessionOptions session_options = cli::session_options(opt);
  MpiDomain domain(comm, domain_options(scene_with_options(scene, session_options), o));
  OutputTimes written;
  const auto outputs = make_mpi_outputs(domain, opt, o.gather_output, written);  // before the fill
  std::vector<FrameObserver*> observers;
  for (const auto& w : outputs) observers.push_back(w.get());
  const bool shares = spread_restart(scene, session_options);
  Start start = shares ? read_shares(io_comm, scene, session_options)
                       : start_run(comm, rank, scene, session_options);
  std::unique_ptr<Simulation> sim =
      shares
          ? domain.distribute_shares(start.scene, std::move(start.share), start.first, start.total)
          : domain.distribute(start.scene, std::move(start.full));
  RunSession session(start.scene, session_options, std::move(sim), start.restart,
                     start.auto_choice);
  if (rank == 0) cli::print_session_choices(session);
  const bool frames_taken = opt.frame_outputs();
  const std::uint64_t every = cli::frame_every(opt, session.plan().turn_steps, frames_taken);
  MPI_Barrier(comm);
  const double t0 = MPI_Wtime();
  const double comm0 = domain.comm_seconds();  // the distribution is not part of the stepping
  const TurnResult turn = cli::settle_and_turn(session, every, observers, rank == 0);
  const double seconds = MPI_Wtime() - t0;
  const double comm_share = seconds > 0.0 ? (domain.comm_seconds() - comm0) / seconds : 0.0;
  const Simulation& run = session.simulation();
  cli::RunSummary summary = cli::run_summary(run, turn.stats, domain.particles());
  reduce_phase(domain, summary.phase);
  const MpiRunSummary decomposition = decomposition_summary(domain, run, o, comm_share, written);
  if (rank == 0) {
    cli::print_summary(summary);
    cli::print_team(session);
    print_decomposition(decomposition);
  }
}

}  // namespace drumlab::mpi
