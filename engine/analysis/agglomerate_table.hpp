#pragma once
// The agglomerate table of a run or a series (`run --agglomerates FILE.csv`, `analyze`): one CSV
// row per frame (agglomerate_csv_header). Rows are streamed to FILE.csv.part and flushed as they
// come; finish() renames the file into place. A killed or failed run therefore leaves at most a
// .part file, never a file under the final name that looks complete.
#include <filesystem>
#include <fstream>
#include <vector>

#include "engine/analysis/agglomerates.hpp"

namespace drumlab {

class AgglomerateTable {
 public:
  /// Opens FILE.part; throws InputError naming the file if it cannot be created.
  explicit AgglomerateTable(std::filesystem::path file);
  /// Removes the .part file of an unfinished table only if a write failed.
  ~AgglomerateTable();
  AgglomerateTable(const AgglomerateTable&) = delete;
  AgglomerateTable& operator=(const AgglomerateTable&) = delete;

  /// Appends and flushes one row. Throws InputError if it cannot be written (disk full).
  void add(const AgglomerateStats& row);
  /// Closes the file and renames it into place.
  void finish();

  const std::filesystem::path& file() const { return file_; }
  std::filesystem::path part_file() const;
  /// FILE with the extension .png: where the size-distribution chart goes.
  std::filesystem::path chart_file() const;
  const std::vector<AgglomerateStats>& rows() const { return rows_; }

 private:
  std::filesystem::path file_;
  std::ofstream out_;
  std::vector<AgglomerateStats> rows_;
  bool finished_ = false;
};

/// The rows of a finished table (FILE.csv as AgglomerateTable writes it), for its chart drawn
/// afterwards (`drumlab analyze FILE.csv`). Throws InputError naming the file and line if it
/// cannot be read, its header is not the table's or a row does not parse.
std::vector<AgglomerateStats> read_agglomerate_table(const std::filesystem::path& file);

}  // namespace drumlab
