#include "engine/analysis/agglomerate_table.hpp"

#include <charconv>
#include <sstream>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab {

AgglomerateTable::AgglomerateTable(std::filesystem::path file)
    : table_(std::move(file), agglomerate_csv_header(), "--agglomerates") {}

std::filesystem::path AgglomerateTable::chart_file() const {
  std::filesystem::path png = file();
  png.replace_extension(".png");
  return png;
}

void AgglomerateTable::add(const AgglomerateStats& row) {
  table_.add(agglomerate_csv_row(row));
  rows_.push_back(row);
}

void AgglomerateTable::finish() {
  table_.finish();
}

namespace {

/// The fields of one CSV row (the table has no quoted fields: the criterion has no comma).
std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

template <class T>
bool parse(const std::string& text, T& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end;
}

/// The header of tables written before the spray's columns (their rows have 13 fields).
constexpr std::string_view kHeaderWithoutSpray =
    "time,criterion,agglomerates,mean_size,largest,d10,d50,d90,bonds,free_liquid,"
    "bridge_liquid,wall_bridge_liquid,largest_plain_share";
/// The header of tables written before the wall film's column (their rows have 16 fields).
constexpr std::string_view kHeaderWithoutWallFilm =
    "time,criterion,agglomerates,mean_size,largest,d10,d50,d90,bonds,free_liquid,"
    "bridge_liquid,wall_bridge_liquid,largest_plain_share,sprayed_liquid,airborne_liquid,"
    "lost_liquid";

bool parse_row(const std::vector<std::string>& f, std::size_t fields, AgglomerateStats& s) {
  if (f.size() != fields) return false;
  s.criterion = f[1];
  const bool common = parse(f[0], s.time) && parse(f[2], s.count) && parse(f[3], s.mean_size) &&
                      parse(f[4], s.largest) && parse(f[5], s.d10) && parse(f[6], s.d50) &&
                      parse(f[7], s.d90) && parse(f[8], s.bonds) && parse(f[9], s.free_liquid) &&
                      parse(f[10], s.bridge_liquid) && parse(f[11], s.wall_liquid) &&
                      parse(f[12], s.largest_plain_share);
  if (fields == 13) return common;
  const bool spray = common && parse(f[13], s.spray.sprayed) && parse(f[14], s.spray.airborne) &&
                     parse(f[15], s.spray.lost);
  if (fields == 16) return spray;
  return spray && parse(f[16], s.spray.on_wall);
}

}  // namespace

std::vector<AgglomerateStats> read_agglomerate_table(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot read", file.string()));
  std::string line;
  const bool read = static_cast<bool>(std::getline(in, line));
  const std::size_t fields = !read                              ? 0
                             : line == agglomerate_csv_header() ? 17
                             : line == kHeaderWithoutWallFilm   ? 16
                             : line == kHeaderWithoutSpray      ? 13
                                                                : 0;
  if (fields == 0) {
    throw InputError(
        fmt::format("{}:1: not an agglomerate table (its header differs from "
                    "`drumlab run --agglomerates`)",
                    file.string()));
  }
  std::vector<AgglomerateStats> rows;
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    AgglomerateStats s;
    if (!parse_row(fields_of(line), fields, s)) {
      throw InputError(fmt::format("{}:{}: not a row of the table", file.string(), number));
    }
    rows.push_back(s);
  }
  if (rows.empty()) throw InputError(fmt::format("{}: the table has no rows", file.string()));
  return rows;
}

}  // namespace drumlab
