#include "render/vtu_series_writer.hpp"

#include <vtkDataSet.h>
#include <vtkImageData.h>

#include "engine/io/paraview/wall_datasets.hpp"
#include "render/vtk_datasets.hpp"
#include "render/vtk_files.hpp"

namespace drumlab::render {

VtuSeriesWriter::VtuSeriesWriter(std::filesystem::path directory, VtuSeriesOptions options)
    : series_(std::move(directory)), options_(options) {}

void VtuSeriesWriter::write_frame(const Simulation& sim) {
  std::vector<std::pair<std::string, std::string>> files;
  const auto write = [&](const char* stem, const char* ext, vtkDataObject* data) {
    files.emplace_back(stem, series_.file_name(stem, ext));
    write_vtk_xml(data, directory() / files.back().second);
  };
  const paraview::FrameMotion motion = paraview::frame_motion(sim, options_.frame);
  const auto moved = [&](paraview::DataSet d) {
    paraview::to_frame(d, motion);
    return d;
  };
  write("particles", "vtu", to_vtk(moved(paraview::particles(sim, options_.granule))));
  write("drum", "vtp", to_vtk(moved(paraview::drum(sim))));
  if (sim.wall_meshes()) write("walls", "vtp", to_vtk(moved(paraview::walls(sim))));
  if (options_.contacts) write("contacts", "vtp", to_vtk(moved(paraview::contacts(sim))));
  if (sim.scene().drum.orbit.active()) {
    write("carrier", "vtp", to_vtk(paraview::carrier_arm(sim, options_.frame)));
  }
  if (sim.spray() != nullptr) {
    write("droplets", "vtu", to_vtk(paraview::droplets(sim)));
    write("nozzles", "vtp",
          to_vtk(paraview::nozzles(sim.scene().sprays, sim.scene().drum.diameter)));
  }
  if (options_.grid) {
    if (auto image = grid_dataset(sim)) write("grid", "vti", image);
  }
  series_.commit(files, sim.time());  // the collections, once every file of the frame exists
}

void VtuSeriesWriter::write_frame(const SeriesFrame& frame) {
  std::vector<std::pair<std::string, std::string>> files{
      {"particles", series_.file_name("particles", "vtu")}};
  write_vtk_xml(to_vtk(paraview::particles(frame)), directory() / files.back().second);
  if (frame.has_bonds) {
    files.emplace_back("bonds", series_.file_name("bonds", "vtp"));
    write_vtk_xml(to_vtk(paraview::bonds(frame)), directory() / files.back().second);
  }
  series_.commit(files, frame.time);
}

}  // namespace drumlab::render
