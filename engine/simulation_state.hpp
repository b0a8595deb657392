#pragma once
// Everything a Simulation's next step depends on, as plain data: the particles (every array,
// including the forces and torques of the current state, which the next half kick uses), the
// clock, the drum, the contact list with its tangential history, the per-particle wall history and
// a spraying scene's droplets.
// Simulation::state() exports it; Simulation(scene, state) continues bit-identically from it.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/contact/contact_model.hpp"
#include "engine/particles.hpp"
#include "engine/spray/spray_state.hpp"

namespace drumlab {

struct SimulationState {
  Particles particles;
  double time = 0.0;        ///< s
  double dt = 0.0;          ///< s
  double drum_omega = 0.0;  ///< rad/s
  double drum_angle = 0.0;  ///< rad
  /// A planetary drum's carrier ([drum.orbit]): its angle (rad) and its current rate (rad/s, 0
  /// while it stands, as in settling); both 0 without an orbit.
  double carrier_angle = 0.0;
  double carrier_omega = 0.0;
  std::uint64_t steps = 0;
  std::string search_method;
  /// Contact list in CSR form (see ContactList): rows = particles + 1 entries, or empty.
  std::vector<std::size_t> contact_row_start;
  std::vector<Index> contact_col;
  std::vector<Vec3> contact_history;  ///< tangential displacement per contact, m
  /// The law parts' scalars per contact (ContactList::state()): contact_state_size per contact.
  std::size_t contact_state_size = 0;
  std::vector<double> contact_state;
  WallHistory wall_history;  ///< per particle, per wall part, m
  SprayState spray;          ///< the droplets and the wall film ([[spray]]; empty without)
};

}  // namespace drumlab
