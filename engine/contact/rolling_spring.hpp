#pragma once
// Rolling resistance as a spring, a dashpot and a Coulomb limit (MercuryDPM's FrictionSpecies
// rolling part, Kernel/Interactions/FrictionForceInteractions/FrictionInteraction.cc:108-171,
// after Luding 2008), beside the constant-torque RollingResistance (rolling_resistance.hpp), which
// stays drumlab's default. With n the unit normal towards i and omega_rel = omega_i - omega_j:
//     v_r  = -2 R* n x omega_rel                           (rolling velocity)
//     xi_r <- xi_r + (v_r - (xi_r . v_ij) n / |d|) dt      (pair; a wall: without the correction)
//     F_r  = -k_r xi_r - gamma_r v_r,  |F_r| <= mu_r |F_n| (else scaled onto the limit and xi_r
//                                                          set so that spring and dashpot give it)
//     M_i  = 2 R* n x F_r,   M_j = -M_i.
// The largest torque is mu_r |F_n| 2 R*, twice RollingResistance's mu_r R* |F_n| for the same
// mu_r. The spring is symmetric under the swap of i and j (n and omega_rel both change sign), so a
// re-ordering that flips a pair moves it without negating it. No twisting resistance (the peer's
// torsion coefficient is 0 in its drum).
//
// Composed by ContactModel with `[contact] rolling = "spring"`: a pair keeps xi_r as the last
// kRollingStateSize scalars of its contact state (ContactList::state(): carried by the merge,
// moved without negation at re-ordering, saved in checkpoints, packed for MPI); a particle keeps
// one xi_r per wall part in the per-particle arrays kWallRollingArrays. Like the sliding spring,
// xi_r is reset when the overlap ends.
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <string_view>

#include "engine/contact/lane_vec.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// Scalars of a pair's rolling spring in its contact state (xi_r: x, y, z; m).
inline constexpr std::size_t kRollingStateSize = 3;

/// The per-particle arrays of each particle's rolling spring against each wall part (mantle, low
/// cap, high cap), component by component (m): registered by a scene with a rolling spring at
/// the wall, carried by re-ordering, checkpoints and MPI migration like every array.
inline constexpr std::array<std::array<std::string_view, 3>, 3> kWallRollingArrays = {{
    {"wall_rolling_x_mantle", "wall_rolling_y_mantle", "wall_rolling_z_mantle"},
    {"wall_rolling_x_low_cap", "wall_rolling_y_low_cap", "wall_rolling_z_low_cap"},
    {"wall_rolling_x_high_cap", "wall_rolling_y_high_cap", "wall_rolling_z_high_cap"},
}};

struct RollingSpring {
  double stiffness = 0.0;  ///< k_r, N/m (the peer: 2/7 of the normal k)
  double damping = 0.0;    ///< gamma_r, kg/s (the peer: 2/7 of the normal gamma)
  double friction = 0.0;   ///< mu_r (dimensionless)

  /// Advances the rolling spring xi (m) of one contact over dt and returns the torque on i
  /// (N m). n: unit normal towards i; omega_rel = omega_i - omega_j (rad/s); v_ij = v_i - v_j and
  /// inv_dist = 1 / |x_i - x_j| for a pair (inv_dist = 0 at a wall); fn_abs = |F_n| (N).
  Vec3 torque(Vec3& xi, const Vec3& n, const Vec3& omega_rel, const Vec3& v_ij, double inv_dist,
              double r_eff, double fn_abs, double dt) const {
    return torque_of<Vec3>(xi, n, omega_rel, v_ij, inv_dist, r_eff, fn_abs, dt);
  }
  LaneVec torque(LaneVec& xi, const LaneVec& n, const LaneVec& omega_rel, const LaneVec& v_ij,
                 double inv_dist, double r_eff, double fn_abs, double dt) const {
    return torque_of<LaneVec>(xi, n, omega_rel, v_ij, inv_dist, r_eff, fn_abs, dt);
  }

 private:
  template <class V>
  [[gnu::always_inline]] V torque_of(V& xi, const V& n, const V& omega_rel, const V& v_ij,
                                     double inv_dist, double r_eff, double fn_abs,
                                     double dt) const {
    const double arm = 2.0 * r_eff;
    const V v_r = -arm * n.cross(omega_rel);
    xi = xi + (v_r - (xi.dot(v_ij) * inv_dist) * n) * dt;
    V f = -stiffness * xi - damping * v_r;
    const double limit = friction * fn_abs;
    const double f2 = f.squaredNorm();
    const bool rolling = f2 > limit * limit;
    const double cap = limit / std::sqrt(f2);
    f *= rolling ? cap : 1.0;
    const V xi_limit = -(f + damping * v_r) * (1.0 / stiffness);
    xi = select(rolling, xi_limit, xi);
    return arm * n.cross(f);
  }
};

}  // namespace drumlab
