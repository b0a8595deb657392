#pragma once
// --vtu DIR where VTK cannot be linked (drumlab-mpi, whose MPI HDF5 must not meet VTK's serial one;
// a build without the render library): the frames `drumlab run --vtu` writes with VTK
// (render/vtu_series_writer.hpp: particles_NNNNNN.vtu, drum_NNNNNN.vtp, walls_NNNNNN.vtp with
// triangle walls, contacts_NNNNNN.vtp on request, their .pvd collections), the same datasets
// (engine/io/paraview/frame_datasets.hpp, wall_datasets.hpp) written by the plain XML writer:
// uncompressed raw appended data, ParaView reads both alike. No grid occupancy (it needs VTK's
// image data and a live search grid).
#include <filesystem>
#include <string>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/io/paraview/pvd_series.hpp"
#include "engine/io/paraview/view_frame.hpp"
#include "engine/simulation.hpp"

namespace drumlab::cli {

class PlainVtuSeries {
 public:
  /// Creates `directory` if needed; throws InputError if it cannot.
  PlainVtuSeries(const std::string& directory, bool contacts, const GranuleCriterion& granule,
                 paraview::ViewFrame frame = paraview::ViewFrame::drum);
  /// One frame of the whole state (a serial simulation, or the state a decomposed run gathered).
  void write_frame(const Simulation& whole);

  const std::filesystem::path& directory() const { return series_.directory(); }
  std::size_t frames() const { return series_.frames(); }

 private:
  paraview::PvdSeries series_;
  bool contacts_;
  GranuleCriterion granule_;
  paraview::ViewFrame frame_;
};

}  // namespace drumlab::cli
