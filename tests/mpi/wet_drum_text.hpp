#pragma once
// The small wet (or cohesive) drum the mpi tests run on several ranks and serially.
#include <string>

#include "tests/small_drum_text.hpp"

namespace drumlab::test {

inline constexpr double kLiquidContent = 0.02;

/// 700 particles (three of the pair loop's blocks of 256 rows, pair_block_rows) packed by strong
/// gravity in a few steps, re-ordered every 30 steps, a small Verlet skin so that particles migrate
/// often; `law`: the [liquid] or [cohesion] table; `ends`: "" (caps) or "periodic".
inline std::string scene_text(const std::string& law, const std::string& ends = "") {
  SmallDrumText t;
  t.ends = ends;
  t.search = "verlet:m2";
  t.omega = "6.0";
  t.time = "dt_factor = 0.2\nduration = 0.01";
  t.output = "diagnostics_every = 50";
  t.depth = "0.1";
  t.fill = "count = 700\nsettle_time = 0.004\nseed = 3";
  t.gravity = "[0.0, -150.0, 0.0]";
  return t.text() + "[performance]\nsort_every = 30\nverlet_skin = 0.1\npair_block_rows = 256\n" +
         law;
}

/// Migration (films), wall bridges (on by default), half the liquid seeded in the bridges of the
/// first contacts, a viscous term or not (without: pass 1 runs the plain bridge's SIMD batches);
/// bridges of at most 2e-9 m^3 rupture beyond ~1.3 mm.
inline std::string wet_law(bool viscous = true) {
  return "[liquid]\nsurface_tension = 0.072\ncontact_angle_deg = 20\nliquid_content = " +
         std::to_string(kLiquidContent) + "\nmax_bridge_volume = 2e-9\nfilm_share = 0.5\n" +
         (viscous ? "viscosity = 0.001\nmin_gap = 1e-5\n" : "");
}

}  // namespace drumlab::test
