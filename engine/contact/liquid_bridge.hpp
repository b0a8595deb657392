#pragma once
// Pendular liquid bridge between two spheres: a law part that acts beyond contact.
//
// Force: Willett, Adams, Johnson & Seville (2000), "Capillary bridges between two spheres",
// Langmuir 16, closed form for a bridge of volume V, with the conventions of MercuryDPM's
// LiquidMigrationWilletInteraction: effective radius R = 2 R1 R2 / (R1 + R2) (a wall: R = 2 Rp),
//     touching (s <= 0):  F = F0 = 2 pi R gamma cos(theta),
//     gap s > 0:          F = F0 / (1 + (1.05 + 2.5 s~) s~),   s~ = s sqrt(R / V),
// attractive, along the line of centres. Gap convention: s is the surface separation
// |x_i - x_j| - (r_i + r_j), negative while the spheres overlap. The bridge forms only on contact
// (s <= 0) and ruptures once s > s_rup = (1 + theta / 2) V^(1/3) (Lian, Thornton & Adams 1993, as
// in MercuryDPM): at s = s_rup it still pulls, beyond it the bridge is gone until the spheres
// touch again.
//
// The beyond-contact part contract (what ContactModel reads from any such part):
//   kStateSize              scalars it keeps per contact (ContactList::state());
//   range()                 the largest surface gap at which it can act (m): the search margin;
//   update(gap, R, dt, state)  advances the contact's state at gap `gap` by dt (s, the time since
//                           the previous evaluation) and returns the attractive normal force
//                           (N), 0 when the interaction has ended;
//   bond(state)             whether the state holds a live link (engine/contact/bond.hpp), and
//   bond_volume / bond_age  what a Bond reports of it.
#include <cmath>
#include <cstddef>
#include <numbers>

namespace drumlab {

struct LiquidBridge {
  /// state[0]: the bridge's liquid volume (m^3), 0: no bridge; state[1]: its age, the time (s)
  /// since it formed (0 without a bridge).
  static constexpr std::size_t kStateSize = 2;

  double surface_tension = 0.0;  ///< gamma, N/m
  double contact_angle = 0.0;    ///< theta, rad
  double volume = 0.0;           ///< V of every bridge (no liquid migration yet), m^3

  LiquidBridge(double gamma, double theta, double v)
      : surface_tension(gamma), contact_angle(theta), volume(v) {}

  /// Willett's effective radius (m) of two spheres, and of a sphere against a wall.
  static double pair_radius(double r1, double r2) { return 2.0 * r1 * r2 / (r1 + r2); }
  static double wall_radius(double r) { return 2.0 * r; }

  /// s_rup = (1 + theta / 2) V^(1/3), m.
  double rupture_distance() const { return (1.0 + 0.5 * contact_angle) * std::cbrt(volume); }
  double range() const { return rupture_distance(); }

  /// Force of an existing bridge of volume v at gap s (N, attractive), for s <= s_rup.
  double force(double gap, double r_eff, double v) const {
    const double f0 = 2.0 * std::numbers::pi * r_eff * surface_tension * std::cos(contact_angle);
    if (gap <= 0.0) return f0;
    const double s = gap * std::sqrt(r_eff / v);
    return f0 / (1.0 + (1.05 + 2.5 * s) * s);
  }

  /// Forms the bridge on contact, ruptures it beyond s_rup, ages a live one by dt; returns its
  /// force (0 without one).
  double update(double gap, double r_eff, double dt, double* state) const {
    const bool lived = state[0] > 0.0;
    if (gap <= 0.0) {
      state[0] = volume;
    } else if (gap > rupture_distance()) {
      state[0] = 0.0;
    }
    if (state[0] == 0.0) {
      state[1] = 0.0;
      return 0.0;
    }
    state[1] = lived ? state[1] + dt : 0.0;
    return force(gap, r_eff, state[0]);
  }

  static bool bond(const double* state) { return state[0] > 0.0; }
  static double bond_volume(const double* state) { return state[0]; }
  static double bond_age(const double* state) { return state[1]; }
};

}  // namespace drumlab
