#include "engine/analysis/agglomerate_table.hpp"

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab {

AgglomerateTable::AgglomerateTable(std::filesystem::path file) : file_(std::move(file)) {
  out_.open(part_file(), std::ios::trunc);
  if (!out_) {
    throw InputError(
        fmt::format("--agglomerates {}: cannot write (does the directory exist?)", file_.string()));
  }
  out_ << agglomerate_csv_header() << '\n';
  out_.flush();
}

AgglomerateTable::~AgglomerateTable() = default;

std::filesystem::path AgglomerateTable::part_file() const {
  return file_.string() + ".part";
}

std::filesystem::path AgglomerateTable::chart_file() const {
  std::filesystem::path png = file_;
  png.replace_extension(".png");
  return png;
}

void AgglomerateTable::add(const AgglomerateStats& row) {
  if (finished_) throw std::logic_error("AgglomerateTable: add after finish");
  out_ << agglomerate_csv_row(row) << '\n';
  out_.flush();
  if (!out_) {
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(part_file(), ignored);
    finished_ = true;
    throw InputError(fmt::format("{}: write failed (disk full?)", file_.string()));
  }
  rows_.push_back(row);
}

void AgglomerateTable::finish() {
  if (finished_) return;
  finished_ = true;
  out_.close();
  std::error_code ec;
  if (out_.fail()) ec = std::make_error_code(std::errc::io_error);
  if (!ec) std::filesystem::rename(part_file(), file_, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(part_file(), ignored);
    throw InputError(fmt::format("{}: cannot write ({})", file_.string(), ec.message()));
  }
}

}  // namespace drumlab
