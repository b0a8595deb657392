#include "engine/io/particle_csv.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace drumlab {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      fields.push_back(trim(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  return fields;
}

double parse_number(std::string_view field, std::string_view source, std::size_t line,
                    std::string_view column) {
  double value = 0.0;
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value);
  if (field.empty() || ec != std::errc() || ptr != end) {
    throw InputError(
        fmt::format("{}:{}: column '{}': '{}' is not a number", source, line, column, field));
  }
  if (!std::isfinite(value)) {
    throw InputError(
        fmt::format("{}:{}: column '{}': value {} is not finite", source, line, column, field));
  }
  return value;
}

}  // namespace

ParticleTable parse_particle_csv(std::string_view text, std::string_view source) {
  std::istringstream in{std::string(text)};
  std::string line;
  std::size_t line_no = 0;
  // Header.
  while (std::getline(in, line)) {
    ++line_no;
    if (!trim(line).empty()) break;
  }
  if (trim(line).empty())
    throw InputError(fmt::format("{}: empty file (expected header x,y,z,r)", source));
  const auto header = split(line);
  constexpr std::array<std::string_view, 4> names{"x", "y", "z", "r"};
  std::array<std::size_t, 4> column{};
  for (std::size_t c = 0; c < names.size(); ++c) {
    const auto it = std::find(header.begin(), header.end(), names[c]);
    if (it == header.end()) {
      throw InputError(fmt::format("{}:{}: header has no column '{}' (expected x,y,z,r)", source,
                                   line_no, names[c]));
    }
    column[c] = static_cast<std::size_t>(it - header.begin());
  }
  constexpr std::array<std::string_view, 3> velocity_names{"vx", "vy", "vz"};
  std::array<std::size_t, 3> velocity_column{};
  std::size_t velocity_found = 0;
  for (std::size_t c = 0; c < velocity_names.size(); ++c) {
    const auto it = std::find(header.begin(), header.end(), velocity_names[c]);
    if (it == header.end()) continue;
    velocity_column[c] = static_cast<std::size_t>(it - header.begin());
    ++velocity_found;
  }
  if (velocity_found != 0 && velocity_found != 3) {
    throw InputError(
        fmt::format("{}:{}: header has {} of the velocity columns vx, vy, vz (give all "
                    "three or none)",
                    source, line_no, velocity_found));
  }
  ParticleTable table;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    const auto fields = split(line);
    if (fields.size() != header.size()) {
      throw InputError(fmt::format("{}:{}: {} fields, the header has {}", source, line_no,
                                   fields.size(), header.size()));
    }
    double v[4];
    for (std::size_t c = 0; c < 4; ++c)
      v[c] = parse_number(fields[column[c]], source, line_no, names[c]);
    if (!(v[3] > 0.0)) {
      throw InputError(fmt::format("{}:{}: column 'r': radius {} must be positive", source, line_no,
                                   fields[column[3]]));
    }
    table.position.emplace_back(v[0], v[1], v[2]);
    table.radius.push_back(v[3]);
    table.line.push_back(line_no);
    if (velocity_found == 3) {
      Vec3 u;
      for (std::size_t c = 0; c < 3; ++c)
        u[static_cast<Eigen::Index>(c)] =
            parse_number(fields[velocity_column[c]], source, line_no, velocity_names[c]);
      table.velocity.push_back(u);
    }
  }
  return table;
}

ParticleTable read_particle_csv(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read particle file", file.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_particle_csv(text.str(), file.string());
}

}  // namespace drumlab
