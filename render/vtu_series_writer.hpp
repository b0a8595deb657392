#pragma once
// The VTU/PVD time series for ParaView. Each frame writes, into one directory,
//   particles_NNNNNN.vtu   particles with their arrays (engine/io/paraview/frame_datasets.hpp)
//   drum_NNNNNN.vtp        the analytic drum wall, turned by the drum angle
//   walls_NNNNNN.vtp       the triangle walls ([[wall.mesh]], [[wall.lifters]]), those attached
//                          to the drum turned by its angle (engine/io/paraview/wall_datasets.hpp)
//   contacts_NNNNNN.vtp    contacts as lines with force magnitude (on request)
//   grid_NNNNNN.vti        contact-search grid occupancy (on request; grid methods only)
//   bonds_NNNNNN.vtp       the bond graph of an HDF5 series frame (drumlab convert)
//   droplets_NNNNNN.vtu    the airborne binder droplets, nozzles_NNNNNN.vtp the nozzles and
//                          their cones or fans (a scene with [[spray]])
//   carrier_NNNNNN.vtp     a planetary drum's central axis and arm ([drum.orbit])
// in the drum frame, or in the lab or carrier frame (VtuSeriesOptions::frame).
// and rewrites particles.pvd, drum.pvd (, walls.pvd, contacts.pvd, grid.pvd, ...) so each is
// always a valid series of the frames written so far. Every file goes through a temporary name and
// a rename.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/io/paraview/pvd_series.hpp"
#include "engine/io/paraview/view_frame.hpp"
#include "engine/io/series_frame.hpp"
#include "engine/simulation.hpp"

namespace drumlab::render {

struct VtuSeriesOptions {
  bool contacts = false;     ///< contacts_NNNNNN.vtp + contacts.pvd
  bool grid = false;         ///< grid_NNNNNN.vti + grid.pvd
  GranuleCriterion granule;  ///< criterion of agglomerate_id (granule_options), s
  /// The frame the datasets are written in (engine/io/paraview/view_frame.hpp; --frame).
  paraview::ViewFrame frame = paraview::ViewFrame::drum;
};

class VtuSeriesWriter {
 public:
  /// Creates `directory` if needed; throws InputError if it cannot.
  VtuSeriesWriter(std::filesystem::path directory, VtuSeriesOptions options);

  /// Writes one frame (numbered from 0 in call order) at the simulation's current time.
  void write_frame(const Simulation& sim);
  /// Writes one frame of an HDF5 series (`drumlab convert`): particles_NNNNNN.vtu with the
  /// arrays the series stores, and for a frame with a bond graph bonds_NNNNNN.vtp + bonds.pvd
  /// (bonds_dataset). The series holds no drum geometry, forces or contacts.
  void write_frame(const SeriesFrame& frame);

  const std::filesystem::path& directory() const { return series_.directory(); }
  std::size_t frames() const { return series_.frames(); }

 private:
  paraview::PvdSeries series_;
  VtuSeriesOptions options_;
};

}  // namespace drumlab::render
