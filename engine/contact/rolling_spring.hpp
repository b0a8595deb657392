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
// Not yet composed into ContactModel: it needs a second per-contact history (xi_r) in the pair
// and wall loops and the batched kernel (engine/README.md, "The laws against MercuryDPM's
// species").
#include <Eigen/Geometry>
#include <cmath>

#include "engine/contact/lane_vec.hpp"
#include "engine/types.hpp"

namespace drumlab {

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
