#pragma once
// What a particle is coloured by: the colour modes with their names (the command line's and the
// GUI's), each particle's value, and the map a frame draws them with (range, legend title,
// named categories). No VTK type: drum_view.cpp turns a ColorMap into VTK's lookup table.
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/analysis/granule_criterion.hpp"
#include "engine/session/frame_snapshot.hpp"
#include "engine/simulation.hpp"

namespace drumlab::render {

enum class ColorBy { size, speed, omega, id, coordination, agglomerate };

/// Every colour mode with its name on the command line and in the GUI, in menu order (the one
/// table: a new ColorBy value is one more row in particle_colors.cpp).
struct ColorByName {
  ColorBy value;
  std::string_view name;
};
std::span<const ColorByName> color_by_names();
std::string_view color_by_name(ColorBy by);
/// Parses a name of color_by_names() ("size", "speed", ...); throws InputError otherwise.
ColorBy parse_color_by(std::string_view s);
/// The value each particle (in storage order) is coloured by: radius (mm), speed (m/s), |omega|
/// (rad/s), stable id, or coordination (Simulation::coordination_numbers, periodic ends included,
/// the same count as the VTU's coordination array), or agglomerate: 0 for a particle alone in
/// its agglomerate (grey), else 1 + (agglomerate id mod 7), the colour of the categorical palette
/// (agglomerate_labels with granule, the VTU's agglomerate_id; an agglomerate keeps its
/// colour while it keeps its id).
std::vector<double> particle_color_values(const Simulation& sim, ColorBy by,
                                          const GranuleCriterion& granule = {});

/// How a frame maps its colour values (FrameSnapshot::color_values) to colours.
struct ColorMap {
  std::vector<double> values;
  double lo = 0.0, hi = 1.0;
  std::string title;
  /// Distinct values with their names, drawn as swatches (size classes); empty: a continuous map.
  std::vector<std::pair<double, std::string>> categories;
  bool first_grey = false;  ///< category 0 is grey, the palette starts at category 1
};

/// The map of snapshot `s` coloured by `by`: the range (radii in mm, speeds up to 1.5 times the
/// mantle's speed, ...), the legend's title, and the categories of size classes (the distinct
/// radii, named after the scene's classes, when there are no more than the palette's colours)
/// and of agglomerates (alone, then id mod 7).
ColorMap color_map(const FrameSnapshot& s, ColorBy by);

}  // namespace drumlab::render
