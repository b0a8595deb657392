#pragma once
// A frame of an HDF5 time series (engine/io/h5_series.hpp) as read back, without HDF5: what
// the agglomerate analysis, `drumlab convert` and the ParaView datasets take.
#include <cstdint>
#include <vector>

#include "engine/contact/bond.hpp"
#include "engine/spray/spray_liquid.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// One frame of a series as written (bonds in storage slots). The bond part (mass, film,
/// agglomerate_id, bonds, period, drum_omega) is filled only for a frame with a bond graph
/// (has_bonds); the agglomerate analysis and `drumlab convert` read frames this way.
struct SeriesFrame {
  double time = 0.0;
  std::uint64_t step = 0;
  std::vector<Vec3> position;
  std::vector<Vec3> velocity;
  std::vector<Vec3> omega;
  std::vector<double> radius;
  std::vector<std::uint32_t> id;
  std::vector<std::uint8_t> size_class;
  bool has_bonds = false;
  std::vector<double> mass;
  std::vector<double> film;
  std::vector<std::uint32_t> agglomerate_id;
  std::vector<Bond> bonds;
  double wall_liquid = 0.0;  ///< liquid in wall bridges (frame attribute; 0 in older series)
  SprayLiquid spray{};  ///< sprayed, airborne, lost liquid (frame attributes; 0 in older series)
  double period = 0.0;
  double drum_omega = 0.0;
};

}  // namespace drumlab
