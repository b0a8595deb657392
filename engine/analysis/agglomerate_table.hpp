#pragma once
// The agglomerate table of a run or a series (`run --agglomerates FILE.csv`, `analyze`): one CSV
// row per frame (agglomerate_csv_header), streamed through FILE.csv.part (io/streamed_table.hpp):
// a killed or failed run leaves at most a .part file, never one that looks complete.
#include <filesystem>
#include <vector>

#include "engine/analysis/agglomerates.hpp"
#include "engine/io/streamed_table.hpp"

namespace drumlab {

class AgglomerateTable {
 public:
  /// Opens FILE.part; throws InputError naming the file if it cannot be created.
  explicit AgglomerateTable(std::filesystem::path file);

  /// Appends and flushes one row. Throws InputError if it cannot be written (disk full).
  void add(const AgglomerateStats& row);
  /// Closes the file and renames it into place.
  void finish();

  const std::filesystem::path& file() const { return table_.file(); }
  std::filesystem::path part_file() const { return table_.part_file(); }
  /// FILE with the extension .png: where the size-distribution chart goes.
  std::filesystem::path chart_file() const;
  const std::vector<AgglomerateStats>& rows() const { return rows_; }

 private:
  StreamedTable table_;
  std::vector<AgglomerateStats> rows_;
};

/// The rows of a finished table (FILE.csv as AgglomerateTable writes it), for its chart drawn
/// afterwards (`drumlab analyze FILE.csv`). Throws InputError naming the file and line if it
/// cannot be read, its header is not the table's or a row does not parse.
std::vector<AgglomerateStats> read_agglomerate_table(const std::filesystem::path& file);

}  // namespace drumlab
