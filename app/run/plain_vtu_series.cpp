#include "app/run/plain_vtu_series.hpp"

#include <utility>
#include <vector>

#include "engine/io/paraview/frame_datasets.hpp"
#include "engine/io/paraview/wall_datasets.hpp"
#include "engine/io/paraview/xml_writer.hpp"

namespace drumlab::cli {

PlainVtuSeries::PlainVtuSeries(const std::string& directory, bool contacts,
                               const GranuleCriterion& granule, paraview::ViewFrame frame)
    : series_(directory), contacts_(contacts), granule_(granule), frame_(frame) {}

void PlainVtuSeries::write_frame(const Simulation& whole) {
  std::vector<std::pair<std::string, std::string>> files;
  const paraview::FrameMotion motion = paraview::frame_motion(whole, frame_);
  const auto write = [&](const char* stem, const char* ext, paraview::DataSet d) {
    paraview::to_frame(d, motion);
    files.emplace_back(stem, series_.file_name(stem, ext));
    paraview::write_xml_file(d, directory() / files.back().second);
  };
  write("particles", "vtu", paraview::particles(whole, granule_));
  write("drum", "vtp", paraview::drum(whole));
  if (whole.wall_meshes()) write("walls", "vtp", paraview::walls(whole));
  if (contacts_) write("contacts", "vtp", paraview::contacts(whole));
  if (whole.scene().drum.orbit.active()) {
    files.emplace_back("carrier", series_.file_name("carrier", "vtp"));
    paraview::write_xml_file(paraview::carrier_arm(whole, frame_),
                             directory() / files.back().second);
  }
  if (whole.spray() != nullptr) {
    write("droplets", "vtu", paraview::droplets(whole));
    write("nozzles", "vtp", paraview::nozzles(whole.scene().sprays, whole.scene().drum.diameter));
  }
  series_.commit(files, whole.time());  // the collections, once every file of the frame exists
}

}  // namespace drumlab::cli
