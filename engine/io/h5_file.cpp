#include "engine/io/h5_file.hpp"

#include <algorithm>
#include <fstream>
#include <optional>
#include <system_error>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"
#include "engine/io/h5_journal.hpp"

namespace drumlab::h5 {

/// Switches off HDF5's automatic error printing once; our messages say what failed. First of all
/// (before HDF5 initializes) it asks HDF5 not to close its files at exit: Debian's HDF5 1.10
/// segfaults in its exit handler (H5F__close_cb) on a file whose close failed after a failed
/// disk write (disk full). Every file drumlab opens is closed by its Handle before exit.
void quiet() {
  static const bool done = [] {
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

hsize_t Rows::count() const {
  hsize_t n = 0;
  for (const auto& r : runs) n += r[1];
  return n;
}

const Rows& all_rows() {
  static const Rows all;
  return all;
}

namespace {

/// HDF5's innermost message on its error stack, the cause of the call that just failed ("data
/// error detected by Fletcher32 checksum", "truncated file: eof = ..."); "" if none. H5Ewalk2
/// leaves the stack as it is, so this is taken before any other HDF5 call.
std::string hdf5_cause() {
  std::string cause;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
        if (n == 0 && e->desc != nullptr) *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &cause);
  return cause;
}

std::string file_of(hid_t loc) {
  char buf[1024] = {0};
  if (loc >= 0 && H5Fget_name(loc, buf, sizeof buf) > 0) return buf;
  return "HDF5 file";
}

[[noreturn]] void fail(hid_t loc, const std::string& name, const char* what) {
  throw InputError(fmt::format("{}: {} '{}'", file_of(loc), what, name));
}

/// Throws "<file>: cannot read <kind> '<name>' (damaged or truncated file: <cause>)", `cause` being
/// HDF5's innermost message (taken by hdf5_cause() right after the failed call).
[[noreturn]] void fail_damaged(hid_t loc, const std::string& name, const char* kind,
                               const std::string& cause) {
  throw InputError(fmt::format("{}: cannot read {} '{}' (damaged or truncated file: {})",
                               file_of(loc), kind, name, cause.empty() ? "HDF5 error" : cause));
}

/// Whether `loc` lives in a file written through MPI-IO (engine/io/mpi/): no filters there.
bool parallel_file(hid_t loc) {
#ifdef H5_HAVE_PARALLEL
  Handle file(H5Iget_file_id(loc), H5Fclose);
  Handle fapl(file.get() >= 0 ? H5Fget_access_plist(file.get()) : H5I_INVALID_HID, H5Pclose);
  return fapl.get() >= 0 && H5Pget_driver(fapl.get()) == H5FD_MPIO;
#else
  (void)loc;
  return false;
#endif
}

/// Bytes of the file that holds `loc` (0 if unknown).
hsize_t file_size(hid_t loc) {
  Handle file(H5Iget_file_id(loc), H5Fclose);
  hsize_t size = 0;
  if (file.get() < 0 || H5Fget_filesize(file.get(), &size) < 0) return 0;
  return size;
}

/// A dataset's creation list for a serial file: chunks of whole rows, at most 1 MiB each, with
/// the Fletcher32 checksum, so that a flipped bit in the values is found on reading, not trusted.
/// H5P_DEFAULT (contiguous, unchecked) for a dataset without values or in a parallel file.
Handle checked_layout(hid_t loc, const std::vector<hsize_t>& dims, hid_t file_type) {
  if (dims.empty() || dims[0] == 0 || parallel_file(loc)) return Handle(H5P_DEFAULT, nullptr);
  hsize_t row_bytes = H5Tget_size(file_type);
  for (std::size_t k = 1; k < dims.size(); ++k) row_bytes *= std::max<hsize_t>(dims[k], 1);
  constexpr hsize_t kChunkBytes = 1u << 20;
  std::vector<hsize_t> chunk = dims;
  chunk[0] = std::clamp<hsize_t>(kChunkBytes / std::max<hsize_t>(row_bytes, 1), 1, dims[0]);
  for (std::size_t k = 1; k < chunk.size(); ++k) chunk[k] = std::max<hsize_t>(chunk[k], 1);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (dcpl.get() < 0 ||
      H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()) < 0 ||
      H5Pset_fletcher32(dcpl.get()) < 0) {
    fail(loc, "dataset", "cannot set up the checksummed layout of a");
  }
  return dcpl;
}

hsize_t product(const std::vector<hsize_t>& dims) {
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  return n;
}

/// A parallel writer's check that every rank got here with ok (serial: ok itself).
bool agreed(const Rows& rows, bool ok) {
  return rows.agree ? rows.agree(ok) : ok;
}

/// Selects `rows`' runs (whole rows) in the file space and a memory space of their count.
bool select_rows(hid_t file_space, hid_t mem_space, const Rows& rows, std::size_t rank,
                 const std::vector<hsize_t>& dims) {
  if (rows.runs.empty()) return H5Sselect_none(file_space) >= 0 && H5Sselect_none(mem_space) >= 0;
  std::vector<hsize_t> start(rank, 0), count = dims;
  bool ok = true;
  for (std::size_t k = 0; k < rows.runs.size(); ++k) {
    start[0] = rows.runs[k][0];
    count[0] = rows.runs[k][1];
    ok = ok && H5Sselect_hyperslab(file_space, k == 0 ? H5S_SELECT_SET : H5S_SELECT_OR,
                                   start.data(), nullptr, count.data(), nullptr) >= 0;
  }
  return ok;
}

/// Writes dataset `name`: all of it (serial), or this rank's rows of it (parallel, collective).
void write_raw(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type,
               const void* data, std::vector<hsize_t> dims, const Rows& rows) {
  const std::vector<hsize_t> local = dims;
  if (!rows.all) dims[0] = rows.total;
  if (!rows.all && rows.count() != local[0]) fail(loc, name, "row selection does not match");
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  const Handle layout = checked_layout(loc, dims, file_type);
  Handle set(
      H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, layout.get(), H5P_DEFAULT),
      H5Dclose);
  if (!agreed(rows, space.get() >= 0 && set.get() >= 0)) fail(loc, name, "cannot create dataset");
  static const double dummy = 0.0;  // HDF5 wants a buffer even for zero elements
  bool ok = true;
  if (rows.all) {
    ok = H5Dwrite(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data ? data : &dummy) >= 0;
  } else if (rows.total > 0) {  // a dataset of no rows (a frame without bonds) has nothing to write
    std::vector<hsize_t> mem_dims = local;
    mem_dims[0] = std::max<hsize_t>(local[0], 1);  // a selection of none in a space of one row
    Handle mem(H5Screate_simple(static_cast<int>(dims.size()), mem_dims.data(), nullptr), H5Sclose);
    Handle file_space(H5Dget_space(set.get()), H5Sclose);
    ok = select_rows(file_space.get(), mem.get(), rows, dims.size(), local) &&
         H5Dwrite(set.get(), mem_type, mem.get(), file_space.get(), rows.transfer,
                  data && local[0] > 0 ? data : &dummy) >= 0;
  }
  const bool closed = set.reset();
  if (!agreed(rows, ok && closed)) fail(loc, name, "write failed (disk full?) in dataset");
}

template <class T>
std::vector<T> read_raw(hid_t loc, const std::string& name, hid_t mem_type, H5T_class_t cls,
                        std::size_t expected, const RowRange& range) {
  if (!exists(loc, name)) fail(loc, name, "missing dataset");
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (set.get() < 0) fail(loc, name, "cannot open dataset");
  Handle type(H5Dget_type(set.get()), H5Tclose);
  // The class, the size and (integers) the sign of what was written: a value is never converted.
  if (H5Tget_class(type.get()) != cls || H5Tget_size(type.get()) != sizeof(T) ||
      (cls == H5T_INTEGER && H5Tget_sign(type.get()) != H5T_SGN_NONE)) {
    fail(loc, name, "unexpected element type in dataset");
  }
  Handle space(H5Dget_space(set.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) fail(loc, name, "cannot read the size of dataset");
  if (expected != kAnySize && static_cast<std::size_t>(n) != expected) {
    throw InputError(fmt::format("{}: dataset '{}' has {} values, expected {}", file_of(loc), name,
                                 n, expected));
  }
  // A damaged header can claim more values than the whole file holds: refused before allocating.
  const hsize_t bytes = static_cast<hsize_t>(n) * sizeof(T);
  if (const hsize_t size = file_size(loc); bytes > size) {
    throw InputError(fmt::format(
        "{}: dataset '{}' claims {} values ({} bytes), more than the file's {} bytes (damaged?)",
        file_of(loc), name, n, bytes, size));
  }
  if (range.all) {
    std::vector<T> out(static_cast<std::size_t>(n));
    T dummy{};
    if (H5Dread(set.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, n ? out.data() : &dummy) < 0) {
      fail_damaged(loc, name, "dataset", hdf5_cause());
    }
    return out;
  }
  // Rows [first, first + count) along the first dimension, every row whole.
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 1)), 0);
  if (rank < 1 || H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0 ||
      range.first + range.count > dims[0]) {
    fail(loc, name, "rows out of range in dataset");
  }
  std::vector<hsize_t> start(dims.size(), 0), count(dims);
  start[0] = range.first;
  count[0] = range.count;
  hsize_t values = 1;
  for (const hsize_t c : count) values *= c;
  std::vector<T> out(static_cast<std::size_t>(values));
  if (values == 0) return out;
  Handle memory(H5Screate_simple(1, &values, nullptr), H5Sclose);
  if (H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                          nullptr) < 0 ||
      H5Dread(set.get(), mem_type, memory.get(), space.get(), H5P_DEFAULT, out.data()) < 0) {
    fail_damaged(loc, name, "dataset", hdf5_cause());
  }
  return out;
}

Handle open_attribute(hid_t loc, const std::string& name) {
  if (H5Aexists(loc, name.c_str()) <= 0) fail(loc, name, "missing attribute");
  Handle a(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (a.get() < 0) fail(loc, name, "cannot open attribute");
  return a;
}

void write_scalar_attribute(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type,
                            const void* value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle a(H5Acreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose);
  if (a.get() < 0 || H5Awrite(a.get(), mem_type, value) < 0) {
    fail(loc, name, "cannot write attribute");
  }
}

}  // namespace

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    closer_ = o.closer_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

bool Handle::reset() {
  if (id_ < 0 || closer_ == nullptr) return true;
  const herr_t status = closer_(id_);
  id_ = H5I_INVALID_HID;
  return status >= 0;
}

bool set_format(hid_t fapl, FileFormat format) {
  const H5F_libver_t low = format == FileFormat::whole ? H5F_LIBVER_V110 : H5F_LIBVER_V18;
  return H5Pset_libver_bounds(fapl, low, low) >= 0;
}

namespace {

/// File access without HDF5's file lock (a reader that opens a streamed series between frames,
/// ParaView or h5ls, must not make the writer's next open fail); a new file in `format`.
Handle file_access(const std::filesystem::path& path, std::optional<FileFormat> format) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (fapl.get() < 0 || H5Pset_file_locking(fapl.get(), false, true) < 0 ||
      (format && !set_format(fapl.get(), *format))) {
    throw InputError(fmt::format("{}: cannot set up HDF5 file access", path.string()));
  }
  return fapl;
}

}  // namespace

StagedFile::StagedFile(std::filesystem::path path)
    : path_(std::move(path)), staging_(staging_path(path_)) {
  quiet();
  const Handle fapl = file_access(path_, FileFormat::whole);
  file_ = Handle(H5Fcreate(staging_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  if (file_.get() < 0) throw cannot_create(path_);
}

StagedFile::~StagedFile() {
  if (committed_) return;
  file_.reset();
  std::error_code ignored;
  std::filesystem::remove(staging_, ignored);
}

void StagedFile::write(const std::function<void(hid_t)>& fill) {
  try {
    fill(file_.get());
  } catch (const InputError& e) {  // HDF5 names the temporary: say the file the user asked for
    std::string what = e.what();
    const std::string staging = staging_.string();
    for (std::size_t at = what.find(staging); at != std::string::npos; at = what.find(staging)) {
      what.replace(at, staging.size(), path_.string());
    }
    throw InputError(what);
  }
}

void StagedFile::commit() {
  const bool flushed = H5Fflush(file_.get(), H5F_SCOPE_LOCAL) >= 0;
  const bool closed = file_.reset();
  if (!flushed || !closed) {
    throw InputError(fmt::format("{}: write failed (disk full?)", path_.string()));
  }
  std::error_code ec;
  std::filesystem::rename(staging_, path_, ec);
  if (ec) {
    throw InputError(fmt::format("{}: cannot rename into place: {}", path_.string(), ec.message()));
  }
  committed_ = true;
}

Handle create_disk_file(const std::filesystem::path& path) {
  quiet();
  const Handle fapl = file_access(path, FileFormat::streamed);
  use_journal_driver(fapl.get());
  Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  if (f.get() < 0) throw InputError(fmt::format("{}: cannot create an HDF5 file", path.string()));
  return f;
}

Handle open_file_rw(const std::filesystem::path& path) {
  quiet();
  if (recover_journal(path) == JournalState::in_use) {
    throw InputError(fmt::format(
        "{}: cannot open for writing: its journal {} is held by another process or cannot be "
        "rolled back",
        path.string(), journal_path(path).string()));
  }
  const Handle fapl = file_access(path, std::nullopt);
  use_journal_driver(fapl.get());
  Handle f(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get()), H5Fclose);
  if (f.get() < 0) throw InputError(fmt::format("{}: cannot open for writing", path.string()));
  return f;
}

void flush(hid_t file) {
  if (H5Fflush(file, H5F_SCOPE_LOCAL) < 0) {
    throw InputError(fmt::format("{}: write failed (disk full?)", file_of(file)));
  }
}

void check_writable(const std::filesystem::path& path) {
  const std::filesystem::path probe = staging_path(path);
  std::ofstream out(probe, std::ios::binary | std::ios::trunc);
  const bool ok = static_cast<bool>(out);
  out.close();
  std::error_code ignored;
  std::filesystem::remove(probe, ignored);
  if (!ok) throw cannot_create(path);
}

Handle open_file(const std::filesystem::path& path) {
  quiet();
  if (!std::filesystem::exists(path)) {
    throw InputError(fmt::format("{}: no such file", path.string()));
  }
  // A journal a killed writer left is rolled back first; one in use is read through.
  Handle fapl(H5P_DEFAULT, nullptr);
  if (recover_journal(path) == JournalState::in_use) {
    fapl = file_access(path, std::nullopt);
    use_journal_driver(fapl.get());
  }
  Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (f.get() < 0) {
    const std::string cause = hdf5_cause();
    throw InputError(fmt::format("{}: not an HDF5 file, or a damaged or truncated one{}{}",
                                 path.string(), cause.empty() ? "" : ": ", cause));
  }
  return f;
}

Handle create_group(hid_t loc, const std::string& name) {
  Handle g(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (g.get() < 0) fail(loc, name, "cannot create group");
  return g;
}

Handle open_dataset(hid_t loc, const std::string& name) {
  if (!exists(loc, name)) fail(loc, name, "missing dataset");
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (set.get() < 0) fail(loc, name, "cannot open dataset");
  return set;
}

Handle open_group(hid_t loc, const std::string& name) {
  if (!exists(loc, name)) fail(loc, name, "missing group");
  Handle g(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (g.get() < 0) fail(loc, name, "cannot open group");
  return g;
}

bool exists(hid_t loc, const std::string& name) {
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

std::size_t element_count(hid_t loc, const std::string& name) {
  if (!exists(loc, name)) fail(loc, name, "missing dataset");
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (set.get() < 0) fail(loc, name, "cannot open dataset");
  Handle space(H5Dget_space(set.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) fail(loc, name, "cannot read the size of dataset");
  return static_cast<std::size_t>(n);
}

void write(hid_t loc, const std::string& name, std::span<const double> data,
           std::vector<hsize_t> dims, const Rows& rows) {
  if (product(dims) != data.size()) fail(loc, name, "shape does not match data for");
  write_raw(loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data.data(), std::move(dims), rows);
}

void write(hid_t loc, const std::string& name, std::span<const std::uint64_t> data,
           const Rows& rows) {
  write_raw(loc, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, data.data(), {data.size()}, rows);
}

void write(hid_t loc, const std::string& name, std::span<const std::uint32_t> data,
           const Rows& rows) {
  write_raw(loc, name, H5T_STD_U32LE, H5T_NATIVE_UINT32, data.data(), {data.size()}, rows);
}

void write(hid_t loc, const std::string& name, std::span<const std::uint8_t> data,
           const Rows& rows) {
  write_raw(loc, name, H5T_STD_U8LE, H5T_NATIVE_UINT8, data.data(), {data.size()}, rows);
}

void write_vec3(hid_t loc, const std::string& name, std::span<const Vec3> data, const Rows& rows) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  const double* raw = data.empty() ? nullptr : data.front().data();
  write(loc, name, std::span<const double>(raw, 3 * data.size()), {data.size(), 3}, rows);
}

namespace {

Handle create_growing(hid_t loc, const std::string& name, hid_t file_type) {
  const hsize_t zero = 0, unlimited = H5S_UNLIMITED, chunk = 256;
  Handle space(H5Screate_simple(1, &zero, &unlimited), H5Sclose);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (space.get() < 0 || dcpl.get() < 0 || H5Pset_chunk(dcpl.get(), 1, &chunk) < 0 ||
      (!parallel_file(loc) && H5Pset_fletcher32(dcpl.get()) < 0)) {
    fail(loc, name, "cannot set up growing dataset");
  }
  Handle set(
      H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
      H5Dclose);
  if (set.get() < 0) fail(loc, name, "cannot create dataset");
  return set;
}

void append_raw(hid_t set, hid_t mem_type, const void* value, const Rows& rows) {
  Handle space(H5Dget_space(set), H5Sclose);
  hsize_t n = 0;
  if (space.get() < 0 || H5Sget_simple_extent_dims(space.get(), &n, nullptr) != 1) {
    fail(set, "growing dataset", "cannot read the size of");
  }
  const hsize_t grown = n + 1, one = 1;
  if (!agreed(rows, H5Dset_extent(set, &grown) >= 0)) fail(set, "growing dataset", "cannot extend");
  Handle file_space(H5Dget_space(set), H5Sclose);
  Handle mem_space(H5Screate_simple(1, &one, nullptr), H5Sclose);
  const bool writes = rows.all || !rows.runs.empty();
  const bool selected =
      writes
          ? H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &n, nullptr, &one, nullptr) >= 0
          : H5Sselect_none(file_space.get()) >= 0 && H5Sselect_none(mem_space.get()) >= 0;
  const bool ok = selected && H5Dwrite(set, mem_type, mem_space.get(), file_space.get(),
                                       rows.transfer, value) >= 0;
  if (!agreed(rows, ok)) fail(set, "growing dataset", "write failed (disk full?) in");
}

}  // namespace

Handle create_growing_doubles(hid_t loc, const std::string& name) {
  return create_growing(loc, name, H5T_IEEE_F64LE);
}
Handle create_growing_u64(hid_t loc, const std::string& name) {
  return create_growing(loc, name, H5T_STD_U64LE);
}
void append(hid_t set, double value, const Rows& rows) {
  append_raw(set, H5T_NATIVE_DOUBLE, &value, rows);
}
void append(hid_t set, std::uint64_t value, const Rows& rows) {
  append_raw(set, H5T_NATIVE_UINT64, &value, rows);
}

std::vector<double> read_doubles(hid_t loc, const std::string& name, std::size_t expected,
                                 const RowRange& range) {
  return read_raw<double>(loc, name, H5T_NATIVE_DOUBLE, H5T_FLOAT, expected, range);
}
std::vector<std::uint64_t> read_u64(hid_t loc, const std::string& name, std::size_t expected,
                                    const RowRange& range) {
  return read_raw<std::uint64_t>(loc, name, H5T_NATIVE_UINT64, H5T_INTEGER, expected, range);
}
std::vector<std::uint32_t> read_u32(hid_t loc, const std::string& name, std::size_t expected,
                                    const RowRange& range) {
  return read_raw<std::uint32_t>(loc, name, H5T_NATIVE_UINT32, H5T_INTEGER, expected, range);
}
std::vector<std::uint8_t> read_u8(hid_t loc, const std::string& name, std::size_t expected,
                                  const RowRange& range) {
  return read_raw<std::uint8_t>(loc, name, H5T_NATIVE_UINT8, H5T_INTEGER, expected, range);
}

std::size_t rows_of(hid_t loc, const std::string& name) {
  if (!exists(loc, name)) fail(loc, name, "missing dataset");
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (set.get() < 0) fail(loc, name, "cannot open dataset");
  Handle space(H5Dget_space(set.get()), H5Sclose);
  hsize_t dims[8] = {};
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 1 || rank > 8 || H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0) {
    fail(loc, name, "cannot read the size of dataset");
  }
  return static_cast<std::size_t>(dims[0]);
}

void check_row_shape(hid_t loc, const std::string& name, std::initializer_list<hsize_t> row_shape) {
  if (!exists(loc, name)) fail(loc, name, "missing dataset");
  Handle set(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (set.get() < 0) fail(loc, name, "cannot open dataset");
  Handle space(H5Dget_space(set.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  hsize_t dims[H5S_MAX_RANK] = {};
  if (rank < 0 || H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0) {
    fail(loc, name, "cannot read the size of dataset");
  }
  const auto wanted = static_cast<int>(row_shape.size()) + 1;
  bool same = rank == wanted;
  for (std::size_t k = 0; same && k < row_shape.size(); ++k) {
    same = dims[k + 1] == row_shape.begin()[k];
  }
  if (same) return;
  std::string has = rank == 0 ? "scalar" : fmt::format("{}", dims[0]);
  for (int k = 1; k < rank; ++k) has += fmt::format(" x {}", dims[k]);
  std::string expected = "N";
  for (const hsize_t d : row_shape) expected += fmt::format(" x {}", d);
  throw InputError(fmt::format("{}: dataset '{}' has shape ({}), expected ({})", file_of(loc), name,
                               has, expected));
}

std::vector<Vec3> read_vec3(hid_t loc, const std::string& name, std::size_t expected_rows,
                            const RowRange& range) {
  check_row_shape(loc, name, {3});
  const std::size_t expected = expected_rows == kAnySize ? kAnySize : 3 * expected_rows;
  const std::vector<double> flat = read_doubles(loc, name, expected, range);
  if (flat.size() % 3 != 0) fail(loc, name, "not an N x 3 dataset:");
  std::vector<Vec3> out(flat.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = Vec3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  }
  return out;
}

void write_attribute(hid_t loc, const std::string& name, double value) {
  write_scalar_attribute(loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void write_attribute(hid_t loc, const std::string& name, std::uint64_t value) {
  write_scalar_attribute(loc, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value);
}

void write_attribute(hid_t loc, const std::string& name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.empty() ? 1 : value.size());
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  write_scalar_attribute(loc, name, type.get(), type.get(), padded.data());
}

double read_double_attribute(hid_t loc, const std::string& name) {
  Handle a = open_attribute(loc, name);
  double v = 0.0;
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0)
    fail_damaged(loc, name, "attribute", hdf5_cause());
  return v;
}

std::uint64_t read_u64_attribute(hid_t loc, const std::string& name) {
  Handle a = open_attribute(loc, name);
  std::uint64_t v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_UINT64, &v) < 0)
    fail_damaged(loc, name, "attribute", hdf5_cause());
  return v;
}

std::string read_string_attribute(hid_t loc, const std::string& name) {
  Handle a = open_attribute(loc, name);
  Handle type(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) {
    fail(loc, name, "not a fixed-length string attribute");
  }
  std::string v(H5Tget_size(type.get()), '\0');
  if (H5Aread(a.get(), type.get(), v.data()) < 0) {
    fail_damaged(loc, name, "attribute", hdf5_cause());
  }
  v.resize(v.find('\0') == std::string::npos ? v.size() : v.find('\0'));
  return v;
}

}  // namespace drumlab::h5
