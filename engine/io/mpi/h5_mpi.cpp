#include "engine/io/mpi/h5_mpi.hpp"

#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"
#include "engine/parallel/particle_pack.hpp"

namespace drumlab::h5 {

bool all_ok(MPI_Comm comm, bool ok) {
  int v = ok ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_MIN, comm);
  return v != 0;
}

void on_root(MPI_Comm comm, const std::function<void()>& work) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0) {
    try {
      work();
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  int length = static_cast<int>(error.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  error.resize(static_cast<std::size_t>(length));
  MPI_Bcast(error.data(), length, MPI_CHAR, 0, comm);
  if (length > 0) throw InputError(error);
}

namespace {

/// As the serial files (engine/io/h5_file.hpp, FileFormat): a new file in the format of its
/// form. The datasets of a parallel file stay unfiltered (no Fletcher32): HDF5 1.10.8's
/// collective chunk allocation hung the ranks after one rank's write failed.
Handle mpi_access(MPI_Comm comm, const std::filesystem::path& path,
                  std::optional<FileFormat> format) {
  quiet();
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  const bool ok = fapl.get() >= 0 && H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL) >= 0 &&
                  H5Pset_file_locking(fapl.get(), false, true) >= 0 &&
                  (!format || set_format(fapl.get(), *format));
  if (!all_ok(comm, ok)) {
    throw InputError(fmt::format("{}: cannot set up parallel HDF5 file access", path.string()));
  }
  return fapl;
}

}  // namespace

Handle create_mpi_file(MPI_Comm comm, const std::filesystem::path& path, FileFormat format) {
  const Handle fapl = mpi_access(comm, path, format);
  Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  if (!all_ok(comm, f.get() >= 0)) throw cannot_create(path);
  return f;
}

Handle open_mpi_file_rw(MPI_Comm comm, const std::filesystem::path& path) {
  const Handle fapl = mpi_access(comm, path, std::nullopt);
  Handle f(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get()), H5Fclose);
  if (!all_ok(comm, f.get() >= 0)) {
    throw InputError(fmt::format("{}: cannot open for writing", path.string()));
  }
  return f;
}

void close_mpi_file(MPI_Comm comm, Handle& file, const std::filesystem::path& path) {
  const bool flushed = H5Fflush(file.get(), H5F_SCOPE_LOCAL) >= 0;
  const bool closed = file.reset();
  if (!all_ok(comm, flushed && closed)) {
    throw InputError(fmt::format("{}: write failed (disk full?)", path.string()));
  }
}

hid_t collective_transfer() {
  static const hid_t dxpl = [] {  // kept to the end of the process (never closed after MPI)
    const hid_t d = H5Pcreate(H5P_DATASET_XFER);
    if (d < 0 || H5Pset_dxpl_mpio(d, H5FD_MPIO_COLLECTIVE) < 0) {
      throw std::runtime_error("cannot set up a collective HDF5 transfer");
    }
    return d;
  }();
  return dxpl;
}

Rows rows_of(MPI_Comm comm, hid_t transfer, std::span<const std::uint64_t> rows, hsize_t total) {
  Rows r;
  r.all = false;
  r.total = total;
  r.transfer = transfer;
  r.agree = [comm](bool ok) { return all_ok(comm, ok); };
  for (const std::uint64_t row : rows) add_rows(r, row, 1);
  return r;
}

void add_rows(Rows& r, hsize_t first, hsize_t count) {
  if (count == 0) return;
  if (!r.runs.empty() && r.runs.back()[0] + r.runs.back()[1] == first) {
    r.runs.back()[1] += count;
  } else {
    r.runs.push_back({first, count});
  }
}

OwnedParticles owned_particles(MpiComm& comm, const SimulationState& local,
                               const std::vector<std::uint8_t>& ghost,
                               std::span<const std::uint64_t> slots) {
  OwnedParticles o{empty_like(local.particles), {}, {}, 0};
  std::vector<std::byte> one;
  for (std::size_t i = 0; i < local.particles.size(); ++i) {
    if (ghost[i] != 0) continue;
    one.clear();
    pack_particle(local.particles, i, slots[i], local.wall_history[i], one);
    std::size_t pos = 0;
    o.slot.push_back(unpack_particle(one, pos, o.particles, o.wall));
  }
  o.total = comm.sum(std::uint64_t{o.slot.size()});
  return o;
}

}  // namespace drumlab::h5
