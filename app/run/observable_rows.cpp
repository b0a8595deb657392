#include "app/run/observable_rows.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "engine/analysis/drum_observables.hpp"
#include "engine/spray/droplet_cloud.hpp"

namespace drumlab::cli {

std::string observable_columns() {
  return "time,revolutions,angle_fit_deg,angle_com_deg,flowing_layer,bed_depth,"
         "surface_curvature,relative_speed,airborne_fraction,free_liquid,bridge_liquid,"
         "wall_liquid,bridges,sprayed_liquid,airborne_liquid,lost_liquid,wall_film_liquid,"
         "upper_fraction,com_offset,wall_speed,field,drum_radius";
}

ObservableRows::ObservableRows(std::filesystem::path file)
    : table_(std::move(file), observable_columns(), "--observables") {}

void ObservableRows::add(const Simulation& whole) {
  const DrumObservables o = measure_drum(whole);
  const LiquidTotals liquid = whole.liquid();
  SprayTotals spray;
  if (const DropletCloud* cloud = whole.spray()) spray = cloud->totals();
  const double fit =
      o.surface_found ? o.angle_of_repose_deg : std::numeric_limits<double>::quiet_NaN();
  last_angle_ = o.com_angle_deg;
  table_.add(
      fmt::format("{:.9g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.17g},{:.17g},"
                  "{:.17g},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}",
                  whole.time(), whole.drum_angle() / (2.0 * std::numbers::pi), fit, o.com_angle_deg,
                  o.flowing_layer_thickness, o.bed_depth, o.surface_curvature, o.relative_speed,
                  o.airborne_fraction, liquid.films, liquid.bridges, liquid.wall_bridges,
                  liquid.bridge_count, spray.sprayed, spray.airborne, spray.lost, spray.on_wall,
                  o.upper_fraction, o.com_offset, o.wall_speed, o.field, o.radius));
}

void ObservableRows::finish() {
  table_.finish();
  fmt::print("observables       {} frames in {}; last frame: angle {:.1f} deg (centre of mass)\n",
             table_.rows(), table_.file().string(), last_angle_);
}

}  // namespace drumlab::cli
