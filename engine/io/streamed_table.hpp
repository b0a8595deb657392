#pragma once
// A CSV table written row by row while a run goes: rows stream to FILE.part and are flushed as
// they come; finish() renames the file into place. A killed or failed run therefore leaves at most
// a .part file (its rows so far), never a file under the final name that looks complete.
#include <filesystem>
#include <fstream>
#include <string>

namespace drumlab {

class StreamedTable {
 public:
  /// Opens FILE.part and writes `header`; throws InputError naming `flag` and the file if it
  /// cannot be created.
  StreamedTable(std::filesystem::path file, const std::string& header, const char* flag);

  /// Appends and flushes one line. Throws InputError if it cannot be written (disk full): the
  /// .part file is removed.
  void add(const std::string& row);
  /// Closes the file and renames it into place (once). Throws InputError if that fails.
  void finish();

  const std::filesystem::path& file() const { return file_; }
  std::filesystem::path part_file() const { return file_.string() + ".part"; }
  std::size_t rows() const { return rows_; }

 private:
  std::filesystem::path file_;
  std::ofstream out_;
  std::size_t rows_ = 0;
  bool finished_ = false;
};

}  // namespace drumlab
