#include "engine/io/paraview/pvd_series.hpp"

#include <algorithm>
#include <sstream>
#include <system_error>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"
#include "engine/types.hpp"

namespace drumlab::paraview {

std::string pvd_text(const std::vector<PvdEntry>& entries) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
  for (const PvdEntry& e : entries) {
    out << fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                       e.time, e.file);
  }
  out << "  </Collection>\n</VTKFile>\n";
  return out.str();
}

PvdSeries::PvdSeries(std::filesystem::path directory) : dir_(std::move(directory)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_)) {
    throw InputError(fmt::format("{}: cannot create output directory{}", dir_.string(),
                                 ec ? ": " + ec.message() : std::string()));
  }
}

std::string PvdSeries::file_name(const std::string& stem, const char* ext) const {
  return fmt::format("{}_{:06d}.{}", stem, frames_, ext);
}

void PvdSeries::commit(const std::vector<std::pair<std::string, std::string>>& files, double time) {
  for (const auto& entry : files) {  // (not a structured binding: clang 14 cannot capture it)
    const std::string& stem = entry.first;
    const std::string& file = entry.second;
    auto it = std::find_if(series_.begin(), series_.end(),
                           [&](const auto& s) { return s.first == stem; });
    if (it == series_.end()) it = series_.insert(series_.end(), {stem, {}});
    it->second.push_back({time, file});
    const std::string text = pvd_text(it->second);
    write_file_atomically(dir_ / (stem + ".pvd"), [&](std::ostream& out) { out << text; });
  }
  ++frames_;
}

}  // namespace drumlab::paraview
