#pragma once
// drumlab-gui --bench: what it measures, the CLI-equivalent run it compares with, the report.
#include <cstdint>

#include "app/gui/frame_profile.hpp"
#include "app/gui/gui_options.hpp"

namespace drumlab::gui {

/// What --bench measured.
struct BenchFigures {
  double paused_fps = 0.0;               ///< frames/s drawn while paused, the camera orbiting
  double still_fps = 0.0;                ///< frames/s paused, the camera still, full size
  double running_fps = 0.0;              ///< frames/s drawn while the simulation runs
  double running_pictures = 0.0;         ///< of those, new snapshots rendered per second
  double gui_particle_steps = 0.0;       ///< particle-steps/s of the simulation inside the GUI
  double gui_wall_particle_steps = 0.0;  ///< particle-steps per wall second while running
  double gui_steps = 0.0;                ///< particle-steps it made while running
  FrameProfile orbiting, still, running;
  double max_running_fps = 0.0;  ///< the pacing while the simulation runs
};

/// The CLI-equivalent run of the GUI's scene: one RunSession, one thread, no window, `steps`
/// turning steps after the settling; particle-steps per second.
double cli_particle_steps(const GuiOptions& options, std::uint64_t steps);
/// Prints --bench's figures.
void print_bench(const GuiOptions& options, const BenchFigures& b, std::uint64_t frames, double cli,
                 std::uint64_t cli_steps);

}  // namespace drumlab::gui
