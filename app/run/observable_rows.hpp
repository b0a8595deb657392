#pragma once
// --observables FILE.csv: the drum observables of every frame
// (engine/analysis/drum_observables.hpp) and the liquid's accounting, a row per frame of the whole
// state (the serial simulation, or the state a decomposed run gathered on rank 0). Rows are
// streamed to FILE.csv.part, flushed as they come, and renamed into place at the end: a killed run
// leaves no file that looks complete. Columns (observable_columns): time (s), revolutions (the
// drum's turn since the start of the turning phase), angle_fit_deg (surface fit; nan without a
// surface), angle_com_deg (from the centre of mass), flowing_layer (m), bed_depth (m),
// surface_curvature, relative_speed (m/s), airborne_fraction, free_liquid, bridge_liquid,
// wall_liquid (m^3: films, pair bridges, wall bridges), bridges (pair bridges), sprayed_liquid,
// airborne_liquid, lost_liquid, wall_film_liquid (m^3, [[spray]]; 0 without): free + bridge + wall
// + airborne + lost + wall_film - sprayed is the scene's initial liquid, conserved to round-off;
// then what the regime rules need (engine/analysis/flow_regime.hpp): upper_fraction, com_offset
// (/ R), wall_speed (m/s, the wall against the field), field (m/s^2, across the axis) and
// drum_radius (m); `drumlab sweep` classifies a window of rows by those rules.
#include <filesystem>
#include <string>

#include "engine/io/streamed_table.hpp"
#include "engine/simulation.hpp"

namespace drumlab::cli {

/// The header line of the table.
std::string observable_columns();

class ObservableRows {
 public:
  /// Opens FILE.part; throws InputError naming the flag and file if it cannot be created.
  explicit ObservableRows(std::filesystem::path file);

  /// Appends and flushes the row of `whole`'s current state; InputError if the write fails.
  void add(const Simulation& whole);
  /// Renames the table into place and prints its line.
  void finish();

 private:
  StreamedTable table_;
  double last_angle_ = 0.0;
};

}  // namespace drumlab::cli
