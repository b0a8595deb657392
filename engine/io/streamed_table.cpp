#include "engine/io/streamed_table.hpp"

#include <system_error>

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab {

StreamedTable::StreamedTable(std::filesystem::path file, const std::string& header,
                             const char* flag)
    : file_(std::move(file)) {
  out_.open(part_file(), std::ios::trunc);
  if (!out_) {
    throw InputError(
        fmt::format("{} {}: cannot write (does the directory exist?)", flag, file_.string()));
  }
  out_ << header << '\n';
  out_.flush();
}

void StreamedTable::add(const std::string& row) {
  if (finished_) throw std::logic_error("StreamedTable: add after finish");
  out_ << row << '\n';
  out_.flush();
  if (!out_) {
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(part_file(), ignored);
    finished_ = true;
    throw InputError(fmt::format("{}: write failed (disk full?)", file_.string()));
  }
  ++rows_;
}

void StreamedTable::finish() {
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
