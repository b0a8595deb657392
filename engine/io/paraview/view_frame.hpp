#pragma once
// The frame a VTU series is written in (`run --frame`). The engine integrates in the drum frame:
// the drum's centre at the origin, its axis along z, not turning (the wall turns in it). With a
// planetary carrier ([drum.orbit]) two more frames exist:
//   lab      the central axis at the origin, not turning: x + c(t), velocities v + c'(t);
//   carrier  turning with the arm about the central axis, the drum's centre fixed at (R_o, 0, z):
//            R(-theta_c) (x + c), velocities R(-theta_c) (v - Omega z x x) (the frame's own
//            motion taken out), angular velocities omega - Omega z: a steady pattern is steady.
// Without an orbit every frame is the drum frame (`carrier` is refused).
#include <string_view>

#include "engine/io/paraview/dataset.hpp"
#include "engine/simulation.hpp"

namespace drumlab::paraview {

enum class ViewFrame { drum, lab, carrier };

/// "drum", "lab" or "carrier"; throws InputError naming `option` for any other name.
ViewFrame parse_view_frame(std::string_view name, std::string_view option);
const char* view_frame_name(ViewFrame frame);

/// The rigid motion from the drum frame to a view frame at one instant: x -> R (x + offset),
/// velocities v -> R (v + velocity_offset - spin z x x), angular velocities omega - spin z,
/// R the rotation about z by `turn`.
struct FrameMotion {
  Vec3 offset = Vec3::Zero();           ///< m
  double turn = 0.0;                    ///< rad
  Vec3 velocity_offset = Vec3::Zero();  ///< m/s
  double spin = 0.0;                    ///< rad/s
  bool identity() const { return offset.isZero(0.0) && turn == 0.0 && spin == 0.0; }
};

/// The motion into `frame` at the simulation's current state. Throws InputError for `carrier`
/// without [drum.orbit].
FrameMotion frame_motion(const Simulation& sim, ViewFrame frame);

/// Moves a dataset into the frame: its points, and its 3-component arrays by name: "velocity"
/// (with the frame's motion; "speed" recomputed), "angular_velocity" (less the spin), every
/// other 3-vector (force) turned.
void to_frame(DataSet& d, const FrameMotion& m);

/// The carrier of a planetary drum as lines in `frame`: the central axis (over the drum's depth)
/// and the arm from it to the drum's axis at both ends. Empty without [drum.orbit].
DataSet carrier_arm(const Simulation& sim, ViewFrame frame);

}  // namespace drumlab::paraview
