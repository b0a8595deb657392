#include "engine/io/mpi/checkpoint_mpi.hpp"

#include <unistd.h>

#include <algorithm>
#include <numeric>
#include <system_error>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"
#include "engine/io/checkpoint_layout.hpp"
#include "engine/io/mpi/h5_mpi.hpp"

namespace drumlab {
namespace {

/// This rank's share of the checkpoint: its owned particles, their contact records (col as
/// serial slots, each row's records by partner slot as the serial list holds them) and
/// row_start values, with the rows of each kind.
struct Share {
  SimulationState state;
  CheckpointRows rows;
};

/// Appends owned particle i's records (local state s) to out, by partner slot.
void row_records(const SimulationState& s, std::size_t i, std::span<const std::uint64_t> slots,
                 SimulationState& out) {
  const std::size_t ss = s.contact_state_size;
  std::vector<std::size_t> k(s.contact_row_start[i + 1] - s.contact_row_start[i]);
  std::iota(k.begin(), k.end(), s.contact_row_start[i]);
  std::sort(k.begin(), k.end(), [&](std::size_t x, std::size_t y) {
    return slots[s.contact_col[x]] < slots[s.contact_col[y]];
  });
  for (const std::size_t q : k) {
    out.contact_col.push_back(static_cast<Index>(slots[s.contact_col[q]]));
    out.contact_history.push_back(s.contact_history[q]);
    out.contact_state.insert(out.contact_state.end(), s.contact_state.begin() + q * ss,
                             s.contact_state.begin() + (q + 1) * ss);
  }
}

/// The first record of each owned particle's row in the whole file: the runs' record counts
/// all-gathered and summed in row order. Returns the total record count.
std::uint64_t record_offsets(MpiComm& comm, const h5::Rows& particle_rows,
                             std::span<const std::uint64_t> counts,
                             std::vector<std::uint64_t>& first) {
  std::vector<std::uint64_t> mine;  // (first row, records) per run
  std::size_t i = 0;
  for (const auto& run : particle_rows.runs) {
    std::uint64_t m = 0;
    for (hsize_t k = 0; k < run[1]; ++k) m += counts[i + k];
    mine.insert(mine.end(), {run[0], m});
    i += run[1];
  }
  const std::vector<std::uint64_t> all = comm.all_gather(mine);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> runs(all.size() / 2);
  for (std::size_t k = 0; k < runs.size(); ++k) runs[k] = {all[2 * k], all[2 * k + 1]};
  std::sort(runs.begin(), runs.end());
  std::uint64_t total = 0;
  std::size_t ours = 0;  // our runs come in the same (row) order
  i = 0;
  for (const auto& [row, m] : runs) {
    if (ours < particle_rows.runs.size() && particle_rows.runs[ours][0] == row) {
      std::uint64_t at = total;  // our run: its rows' first records
      for (hsize_t k = 0; k < particle_rows.runs[ours][1]; ++k, ++i) {
        first.push_back(at);
        at += counts[i];
      }
      ++ours;
    }
    total += m;
  }
  return total;
}

Share make_share(MpiComm& comm, const Simulation& sim, std::span<const std::uint64_t> slots,
                 hid_t transfer) {
  const SimulationState local = sim.state();
  const auto& ghost = sim.ghost_mask();
  h5::OwnedParticles o = h5::owned_particles(comm, local, ghost, slots);
  Share s;
  s.state = local;
  s.state.particles = std::move(o.particles);
  s.state.wall_history = std::move(o.wall);
  s.state.contact_col.clear();
  s.state.contact_history.clear();
  s.state.contact_state.clear();
  std::vector<std::uint64_t> counts;
  for (std::size_t i = 0; i + 1 < local.contact_row_start.size(); ++i) {
    if (ghost[i] != 0) continue;
    counts.push_back(local.contact_row_start[i + 1] - local.contact_row_start[i]);
    row_records(local, i, slots, s.state);
  }
  counts.resize(o.slot.size(), 0);  // a local list without rows: no records
  const MPI_Comm c = comm.comm();
  s.rows.particles = h5::rows_of(c, transfer, o.slot, o.total);
  std::vector<std::uint64_t> first;
  const std::uint64_t records = record_offsets(comm, s.rows.particles, counts, first);
  s.rows.records = h5::rows_of(c, transfer, {}, records);
  for (std::size_t k = 0; k < first.size(); ++k) h5::add_rows(s.rows.records, first[k], counts[k]);
  // row_start: N + 1 entries; the owner of the last row also writes the end (the total).
  std::vector<std::uint64_t> start_rows = o.slot;
  if (!o.slot.empty() && o.slot.back() + 1 == o.total) {
    start_rows.push_back(o.total);
    first.push_back(records);
  }
  s.rows.row_start = h5::rows_of(c, transfer, start_rows, o.total + 1);
  s.state.contact_row_start.assign(first.begin(), first.end());
  return s;
}

/// staging_path with rank 0's pid, the same name on every rank.
std::filesystem::path temporary(MPI_Comm comm, const std::filesystem::path& file) {
  int pid = static_cast<int>(::getpid());
  MPI_Bcast(&pid, 1, MPI_INT, 0, comm);
  return staging_path(file, pid);
}

}  // namespace

void write_checkpoint_mpi(MpiComm& comm, const Simulation& sim,
                          std::span<const std::uint64_t> slots, const std::filesystem::path& file,
                          const std::string& scene_name) {
  const MPI_Comm c = comm.comm();
  const Share share = make_share(comm, sim, slots, h5::collective_transfer());
  const std::filesystem::path tmp = temporary(c, file);
  std::string error;  // the same on every rank: each step of the write is agreed
  try {
    h5::Handle f = h5::create_mpi_file(c, tmp, h5::FileFormat::whole);
    write_checkpoint_datasets(f.get(), share.state, scene_name, share.rows);
    h5::close_mpi_file(c, f, file);
  } catch (const InputError& e) {
    error = e.what();  // named by the file, not its temporary name
    if (error.rfind(tmp.string(), 0) == 0) error.replace(0, tmp.string().size(), file.string());
  }
  h5::on_root(c, [&] {  // every rank has the same `error`; rank 0 renames or cleans up
    std::error_code ec;
    if (error.empty()) std::filesystem::rename(tmp, file, ec);
    if (ec) error = fmt::format("{}: cannot rename into place: {}", file.string(), ec.message());
    if (error.empty()) return;
    std::filesystem::remove(tmp, ec);
    throw InputError(error);
  });
}

}  // namespace drumlab
