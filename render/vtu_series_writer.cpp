#include "render/vtu_series_writer.hpp"

#include <system_error>

#include <fmt/format.h>
#include <vtkImageData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include "engine/io/atomic_file.hpp"
#include "render/vtk_datasets.hpp"

namespace drumlab::render {

VtuSeriesWriter::VtuSeriesWriter(std::filesystem::path directory, VtuSeriesOptions options)
    : dir_(std::move(directory)), options_(options) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_)) {
    throw InputError(fmt::format("{}: cannot create output directory{}", dir_.string(),
                                 ec ? ": " + ec.message() : std::string()));
  }
}

std::string VtuSeriesWriter::frame_name(const std::string& stem, std::size_t frame,
                                        const char* ext) {
  return fmt::format("{}_{:06d}.{}", stem, frame, ext);
}

void VtuSeriesWriter::add(const std::string& series, const std::string& file, double time) {
  auto it = std::find_if(series_.begin(), series_.end(),
                         [&](const auto& s) { return s.first == series; });
  if (it == series_.end()) it = series_.insert(series_.end(), {series, {}});
  it->second.push_back({time, file});
  const std::string text = pvd_text(it->second);
  write_file_atomically(dir_ / (series + ".pvd"), [&](std::ostream& out) { out << text; });
}

void VtuSeriesWriter::write_frame(const Simulation& sim) {
  const double t = sim.time();
  const std::string particles = frame_name("particles", frames_, "vtu");
  write_vtk_xml(particles_dataset(sim, options_.granule_age), dir_ / particles);
  const std::string drum = frame_name("drum", frames_, "vtp");
  write_vtk_xml(drum_dataset(sim), dir_ / drum);
  std::string contacts, grid;
  if (options_.contacts) {
    contacts = frame_name("contacts", frames_, "vtp");
    write_vtk_xml(contacts_dataset(sim), dir_ / contacts);
  }
  if (options_.grid) {
    if (auto image = grid_dataset(sim)) {
      grid = frame_name("grid", frames_, "vti");
      write_vtk_xml(image, dir_ / grid);
    }
  }
  // The collections are updated only after every file of the frame exists.
  add("particles", particles, t);
  add("drum", drum, t);
  if (!contacts.empty()) add("contacts", contacts, t);
  if (!grid.empty()) add("grid", grid, t);
  ++frames_;
}

void VtuSeriesWriter::write_frame(const SeriesFrame& frame) {
  const std::string particles = frame_name("particles", frames_, "vtu");
  write_vtk_xml(particles_dataset(frame), dir_ / particles);
  std::string bonds;
  if (frame.has_bonds) {
    bonds = frame_name("bonds", frames_, "vtp");
    write_vtk_xml(bonds_dataset(frame), dir_ / bonds);
  }
  add("particles", particles, frame.time);
  if (!bonds.empty()) add("bonds", bonds, frame.time);
  ++frames_;
}

}  // namespace drumlab::render
