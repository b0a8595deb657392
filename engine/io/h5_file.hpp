#pragma once
// Small RAII layer over the HDF5 C API (the serial library, see engine/README.md, section "HDF5")
// for checkpoints and time series: typed 1D/2D datasets and scalar attributes. Every failure
// throws InputError naming the file and the object; HDF5's own error stack printing is switched
// off.
#include <hdf5.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include "engine/types.hpp"

namespace drumlab::h5 {

/// An owned HDF5 identifier (file, group, dataset, ...), closed with `closer` at scope exit.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), closer_(closer) {}
  Handle(Handle&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  hid_t get() const { return id_; }
  /// Closes now; returns false if HDF5 reports an error (e.g. flushing a file failed).
  bool reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*closer_)(hid_t) = nullptr;
};

/// Which rows (first dimension) of a dataset this process writes. Serial (the default): all of
/// them, from data that holds the whole dataset. Parallel (one file that every MPI rank writes its
/// share of, engine/io/mpi/): the dataset has `total` rows and this process writes the rows of
/// `runs` ((first row, count), increasing) from data that holds those rows in that order, with
/// the transfer list `transfer` (collective MPI-IO); `agree(ok)` returns whether every rank
/// succeeded, so that a failure on one rank throws on all of them alike.
struct Rows {
  bool all = true;
  hsize_t total = 0;
  std::vector<std::array<hsize_t, 2>> runs;
  hid_t transfer = H5P_DEFAULT;
  std::function<bool(bool)> agree;
  /// Rows this process writes.
  hsize_t count() const;
};
/// All rows (serial).
const Rows& all_rows();

/// Switches off HDF5's error printing and its exit handler (once); every create/open calls it.
void quiet();

/// The two forms of file drumlab creates. `whole` (checkpoints, written under a temporary name
/// and renamed when closed): HDF5 1.10's format, in which all metadata carries a checksum
/// (superblock 3, version 2 object headers, 1.10 chunk indexes). `streamed` (series, opened and
/// closed frame by frame, readable after a kill): HDF5 1.8's format (superblock 2, version 2
/// object headers: checksummed; chunk indexes of version 1 B-trees: not), because 1.10's marks
/// the file as open for writing in its superblock and every reader then refuses a file whose
/// writer was killed ("file is already open for write", until h5clear).
enum class FileFormat { whole, streamed };
/// Sets a file access list's format bounds for a new file of that form; false if HDF5 refuses.
bool set_format(hid_t fapl, FileFormat format);

/// A file written whole, then moved into place (checkpoints): created as PATH.tmp-PID on disk;
/// commit() closes it and renames it to PATH; destroyed uncommitted (an exception on the way), it
/// removes the temporary, so a failed write never leaves a file under PATH. The file is in the
/// `whole` form and, as in every serial file, each dataset with values is chunked with the
/// Fletcher32 filter (write()): a flipped bit or a cut is found on reading. Debian's HDF5 1.10
/// crashes at exit after a failed disk write (disk full) when it closes the failed file again; HDF5
/// is therefore initialized with H5dont_atexit (files are closed by their Handles).
class StagedFile {
 public:
  /// Throws InputError naming `path` if the temporary cannot be created.
  explicit StagedFile(std::filesystem::path path);
  ~StagedFile();
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  hid_t get() const { return file_.get(); }
  /// Calls `fill` with the file; an InputError from it names PATH rather than the temporary.
  void write(const std::function<void(hid_t)>& fill);
  /// Flushes, closes and renames into place; throws InputError naming the path if it cannot.
  void commit();

 private:
  std::filesystem::path path_, staging_;
  Handle file_;
  bool committed_ = false;
};
/// Creates (truncates) an HDF5 file on disk for a series streamed frame by frame (the `streamed`
/// form, the journal driver of h5_journal.hpp: a process killed before the file closes leaves it
/// as it was; without HDF5's file lock, as open_file_rw: a reader between frames must not stop
/// the writer). Throws InputError naming the path.
Handle create_disk_file(const std::filesystem::path& path);
/// Opens an existing file for appending (the journal driver, after rolling back a journal a
/// killed writer left). Throws InputError naming the path.
Handle open_file_rw(const std::filesystem::path& path);
/// Writes everything HDF5 holds for `file` to disk (H5Fflush); throws InputError naming the
/// file if it cannot (disk full).
void flush(hid_t file);
/// Bytes the memory file's image takes now.
std::size_t memory_file_size(hid_t file);
/// Opens a file read-only, after rolling back a journal a killed writer left (h5_journal.hpp;
/// read through one a live writer holds). Throws InputError naming the path (and HDF5's reason
/// when it is not a readable HDF5 file: a cut, a damaged superblock).
Handle open_file(const std::filesystem::path& path);
/// Throws InputError unless a file can be created in the directory of `path` (checked by creating
/// and removing a temporary file there).
void check_writable(const std::filesystem::path& path);

Handle create_group(hid_t loc, const std::string& name);
Handle open_dataset(hid_t loc, const std::string& name);
Handle open_group(hid_t loc, const std::string& name);
bool exists(hid_t loc, const std::string& name);
/// Number of values in a dataset (product of its dimensions); throws InputError if missing.
std::size_t element_count(hid_t loc, const std::string& name);

/// Writes a dataset of shape dims (row-major). data.size() must equal the product of dims. In a
/// serial file a dataset with values is chunked (whole rows, at most 1 MiB a chunk) and
/// checksummed (Fletcher32); a parallel (MPI-IO) file's datasets are contiguous.
/// With `rows` (a parallel writer's share), dims[0] is the number of rows this process writes.
void write(hid_t loc, const std::string& name, std::span<const double> data,
           std::vector<hsize_t> dims, const Rows& rows = all_rows());
void write(hid_t loc, const std::string& name, std::span<const std::uint64_t> data,
           const Rows& rows = all_rows());
void write(hid_t loc, const std::string& name, std::span<const std::uint32_t> data,
           const Rows& rows = all_rows());
void write(hid_t loc, const std::string& name, std::span<const std::uint8_t> data,
           const Rows& rows = all_rows());
void write_vec3(hid_t loc, const std::string& name, std::span<const Vec3> data,
                const Rows& rows = all_rows());

/// A 1D chunked dataset of unlimited length (double or u64 elements) that grows by one value at
/// a time (append). In a parallel file every rank appends (collective) and the ranks whose
/// `rows` list any run write the value (the others select none).
Handle create_growing_doubles(hid_t loc, const std::string& name);
Handle create_growing_u64(hid_t loc, const std::string& name);
void append(hid_t set, double value, const Rows& rows = all_rows());
void append(hid_t set, std::uint64_t value, const Rows& rows = all_rows());

/// Rows [first, first + count) of a dataset along its first dimension (every row whole); the
/// default is the whole dataset.
struct RowRange {
  bool all = true;
  hsize_t first = 0, count = 0;
  static RowRange of(hsize_t first, hsize_t count) { return {false, first, count}; }
};

/// Reads a dataset (or the rows `range` of it); throws InputError if it is missing, of another
/// element type (class, size or sign: nothing is converted), its total size (the whole
/// dataset's) differs from `expected` (unless expected is kAnySize), it claims more bytes than
/// the file has, the range exceeds its rows, or HDF5 cannot read it (a checksum error: the
/// message says so).
inline constexpr std::size_t kAnySize = static_cast<std::size_t>(-1);
std::vector<double> read_doubles(hid_t loc, const std::string& name, std::size_t expected,
                                 const RowRange& range = {});
std::vector<std::uint64_t> read_u64(hid_t loc, const std::string& name, std::size_t expected,
                                    const RowRange& range = {});
std::vector<std::uint32_t> read_u32(hid_t loc, const std::string& name, std::size_t expected,
                                    const RowRange& range = {});
std::vector<std::uint8_t> read_u8(hid_t loc, const std::string& name, std::size_t expected,
                                  const RowRange& range = {});
std::vector<Vec3> read_vec3(hid_t loc, const std::string& name, std::size_t expected_rows,
                            const RowRange& range = {});
/// Throws InputError "<file>: dataset 'NAME' has shape (250 x 9), expected (N x 3 x 3)" unless
/// the dataset is of rank 1 + row_shape.size() with those dimensions after the first.
void check_row_shape(hid_t loc, const std::string& name, std::initializer_list<hsize_t> row_shape);
/// The rows (first dimension) of a dataset; throws InputError if it is missing.
std::size_t rows_of(hid_t loc, const std::string& name);

void write_attribute(hid_t loc, const std::string& name, double value);
void write_attribute(hid_t loc, const std::string& name, std::uint64_t value);
void write_attribute(hid_t loc, const std::string& name, const std::string& value);
double read_double_attribute(hid_t loc, const std::string& name);
std::uint64_t read_u64_attribute(hid_t loc, const std::string& name);
std::string read_string_attribute(hid_t loc, const std::string& name);

}  // namespace drumlab::h5
