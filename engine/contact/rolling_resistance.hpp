#pragma once
// Rolling resistance, constant directional torque (CDT) model:
//     M_i = -mu_r R* |F_n| omega_rel / |omega_rel|,   omega_rel = omega_i - omega_j,   M_j = -M_i.
// (omega_rel is the full relative rotation rate, so the torque also resists twisting.)
//
// Regularisation: a constant torque that flips sign with omega_rel makes omega_rel chatter around
// zero. Below the threshold rate
//     omega_0 = M_max dt (1/I_i + 1/I_j),   M_max = mu_r R* |F_n|,
// i.e. the relative rate the full torque removes in one step, the torque is linear in omega_rel,
//     M_i = -omega_rel / (dt (1/I_i + 1/I_j)),
// which brings omega_rel to zero in one step instead of overshooting. The two branches meet at
// omega_0, so |M| <= M_max always.
#include "engine/contact/lane_vec.hpp"
#include "engine/types.hpp"

namespace drumlab {

struct RollingResistance {
  double rolling_friction = 0.0;  ///< mu_r (dimensionless)

  /// Torque on i (N m). stop_rate = dt (1/I_i + 1/I_j) (s / (kg m^2)); for a wall 1/I_j = 0.
  Vec3 torque(const Vec3& omega_rel, double fn_abs, double r_eff, double stop_rate) const {
    return torque_of<Vec3>(omega_rel, fn_abs, r_eff, stop_rate);
  }
  /// The same for the vectorized kernel (contact_kernel.hpp).
  LaneVec torque(const LaneVec& omega_rel, double fn_abs, double r_eff, double stop_rate) const {
    return torque_of<LaneVec>(omega_rel, fn_abs, r_eff, stop_rate);
  }

 private:
  template <class V>
  [[gnu::always_inline]] V torque_of(const V& omega_rel, double fn_abs, double r_eff,
                                     double stop_rate) const {
    const double m_max = rolling_friction * r_eff * fn_abs;
    const double w = omega_rel.norm();
    // A select, not a branch, so that a loop over contacts vectorizes (see contact_kernel.hpp);
    // both quotients are computed (the one not selected may be inf).
    const double full = -m_max / w;
    const double linear = -1.0 / stop_rate;
    return (w > m_max * stop_rate ? full : linear) * omega_rel;
  }
};

}  // namespace drumlab
