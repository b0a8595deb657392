#pragma once
// The small two-size drum the tests build their scenes from, as scene-file text: radii 4 and 8 mm
// in equal bulk volume, the demo drum's soft glass-like material, and every knob the tests vary as
// a field (kept as text, so each test's scene reads exactly as it did when written by hand).
#include <string>

namespace drumlab::test {

struct SmallDrumText {
  std::string header;  ///< lines before the search method (e.g. a name)
  std::string search = "m5";
  std::string gravity;  ///< empty: the scene's default
  std::string diameter = "0.2";
  std::string depth = "0.05";
  std::string omega = "2.0";
  std::string ends;  ///< empty: the default (caps)
  std::string restitution = "0.5";
  std::string friction = "0.5";
  std::string rolling_friction;  ///< empty: not set
  std::string wall;              ///< the [wall] table's lines; empty: no [wall] table
  std::string fill = "count = 300\nsettle_time = 0.01";
  std::string time = "dt_factor = 0.2\nduration = 0.01";
  std::string output;  ///< the [output] table's lines; empty: no [output] table

  std::string text() const {
    std::string s = header + "search = \"" + search + "\"\n";
    if (!gravity.empty()) s += "gravity = " + gravity + "\n";
    s += "[drum]\ndiameter = " + diameter + "\ndepth = " + depth + "\nomega = " + omega + "\n";
    if (!ends.empty()) s += "ends = \"" + ends + "\"\n";
    s += "[[particles]]\nradius = 0.004\nvolume_fraction = 0.5\n"
         "[[particles]]\nradius = 0.008\nvolume_fraction = 0.5\n"
         "[material]\ndensity = 2500.0\nyoungs_modulus = 5e6\npoisson_ratio = 0.3\n";
    s += "restitution = " + restitution + "\nfriction = " + friction + "\n";
    if (!rolling_friction.empty()) s += "rolling_friction = " + rolling_friction + "\n";
    if (!wall.empty()) s += "[wall]\n" + wall + "\n";
    s += "[fill]\n" + fill + "\n[time]\n" + time + "\n";
    if (!output.empty()) s += "[output]\n" + output + "\n";
    return s;
  }
};

}  // namespace drumlab::test
