#include "app/run/observable_rows.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <system_error>

#include <fmt/format.h>

#include "engine/analysis/drum_observables.hpp"

namespace drumlab::cli {

std::string observable_columns() {
  return "time,revolutions,angle_fit_deg,angle_com_deg,flowing_layer,bed_depth,"
         "surface_curvature,relative_speed,airborne_fraction,free_liquid,bridge_liquid,"
         "wall_liquid,bridges";
}

ObservableRows::ObservableRows(std::filesystem::path file) : file_(std::move(file)) {
  out_.open(part(), std::ios::trunc);
  if (!out_) {
    throw InputError(
        fmt::format("--observables {}: cannot write (does the directory exist?)", file_.string()));
  }
  out_ << observable_columns() << '\n';
  out_.flush();
}

ObservableRows::~ObservableRows() {
  if (finished_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(part(), ignored);
}

std::filesystem::path ObservableRows::part() const {
  return file_.string() + ".part";
}

void ObservableRows::add(const Simulation& whole) {
  const DrumObservables o = measure_drum(whole);
  const LiquidTotals liquid = whole.liquid();
  const double fit =
      o.surface_found ? o.angle_of_repose_deg : std::numeric_limits<double>::quiet_NaN();
  last_angle_ = o.com_angle_deg;
  out_ << fmt::format(
      "{:.9g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.17g},{:.17g},"
      "{:.17g},{}\n",
      whole.time(), whole.drum_angle() / (2.0 * std::numbers::pi), fit, o.com_angle_deg,
      o.flowing_layer_thickness, o.bed_depth, o.surface_curvature, o.relative_speed,
      o.airborne_fraction, liquid.films, liquid.bridges, liquid.wall_bridges, liquid.bridge_count);
  out_.flush();
  if (!out_) throw InputError(fmt::format("{}: write failed (disk full?)", file_.string()));
  ++rows_;
}

void ObservableRows::finish() {
  if (finished_) return;
  out_.close();
  std::error_code ec;
  if (out_.fail()) ec = std::make_error_code(std::errc::io_error);
  if (!ec) std::filesystem::rename(part(), file_, ec);
  finished_ = true;
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(part(), ignored);
    throw InputError(fmt::format("{}: cannot write ({})", file_.string(), ec.message()));
  }
  fmt::print("observables       {} frames in {}; last frame: angle {:.1f} deg (centre of mass)\n",
             rows_, file_.string(), last_angle_);
}

}  // namespace drumlab::cli
