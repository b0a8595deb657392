#include "app/run/plain_vtu_series.hpp"

#include <utility>
#include <vector>

#include "engine/io/paraview/frame_datasets.hpp"
#include "engine/io/paraview/xml_writer.hpp"

namespace drumlab::cli {

PlainVtuSeries::PlainVtuSeries(const std::string& directory, bool contacts,
                               const GranuleCriterion& granule)
    : series_(directory), contacts_(contacts), granule_(granule) {}

void PlainVtuSeries::write_frame(const Simulation& whole) {
  std::vector<std::pair<std::string, std::string>> files;
  const auto write = [&](const char* stem, const char* ext, const paraview::DataSet& d) {
    files.emplace_back(stem, series_.file_name(stem, ext));
    paraview::write_xml_file(d, directory() / files.back().second);
  };
  write("particles", "vtu", paraview::particles(whole, granule_));
  write("drum", "vtp", paraview::drum(whole));
  if (contacts_) write("contacts", "vtp", paraview::contacts(whole));
  if (whole.spray() != nullptr) {
    write("droplets", "vtu", paraview::droplets(whole));
    write("nozzles", "vtp", paraview::nozzles(whole.scene().sprays, whole.scene().drum.diameter));
  }
  series_.commit(files, whole.time());  // the collections, once every file of the frame exists
}

}  // namespace drumlab::cli
