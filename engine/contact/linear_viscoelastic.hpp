#pragma once
// Linear viscoelastic normal contact with a constant stiffness and a constant damping
// coefficient, set by a collision time and a restitution coefficient for one reference pair
// (MercuryDPM's LinearViscoelasticNormalSpecies::setCollisionTimeAndRestitutionCoefficient):
//     F_n = k delta - gamma v_n,
//     gamma = -(m / t_c) ln e,   k = m/2 (pi^2 / t_c^2 + (gamma / m)^2),
// (v_n = (v_i - v_j) . n, negative while approaching) where m = 2 m* of the reference pair: two
// spheres of the scene's `reference_radius` (the peer passes the mass of one mean particle). That
// pair collides for exactly t_c and leaves with restitution exactly e:
//     t_c(m*) = pi / sqrt(k/m* - (gamma / (2 m*))^2),   e(m*) = exp(-gamma t_c(m*) / (2 m*)).
// Every other pair (other masses; a wall contact, m* = m) keeps k and gamma, so its t_c and e
// differ; drumlab's `linear` law (linear_spring_dashpot.hpp) instead scales gamma with each pair's
// m* and keeps e exact. Not clipped at zero (as the peer's computeNormalForce).
//
// Tangential spring and dashpot (with friction): fixed fractions of the normal ones,
//     k_t = a_k k,   gamma_t = a_g gamma,
// the peer's RotatingDrumWet driver: a_k = a_g = 2/7 (setSlidingStiffness(2/7 k),
// setSlidingDissipation(2/7 gamma)).
#include <cmath>
#include <numbers>

#include "engine/contact/hertz_mindlin.hpp"

namespace drumlab {

struct LinearViscoelastic {
  double stiffness = 0.0;                         ///< k, N/m
  double damping_coefficient = 0.0;               ///< gamma, kg/s
  double tangential_stiffness_ratio = 2.0 / 7.0;  ///< a_k = k_t / k
  double tangential_damping_ratio = 2.0 / 7.0;    ///< a_g = gamma_t / gamma

  /// k and gamma for collision time t_c (s) and restitution e in (0, 1] of a pair with
  /// m = 2 m* (kg), with the peer's operations in the peer's order.
  static LinearViscoelastic from_collision(double collision_time, double restitution, double mass,
                                           double stiffness_ratio, double damping_ratio) {
    LinearViscoelastic law;
    law.damping_coefficient = -mass / collision_time * std::log(restitution);
    const double w = std::numbers::pi / collision_time;
    const double g = law.damping_coefficient / mass;
    law.stiffness = 0.5 * mass * (w * w + g * g);
    law.tangential_stiffness_ratio = stiffness_ratio;
    law.tangential_damping_ratio = damping_ratio;
    return law;
  }

  /// Normal force along n (N), positive repulsive.
  double force(double delta, double vn, double /*r_eff*/, double /*m_eff*/) const {
    return stiffness * delta - damping_coefficient * vn;
  }

  TangentialCoefficients tangential(double /*delta*/, double /*r_eff*/, double /*m_eff*/) const {
    return {tangential_stiffness_ratio * stiffness, tangential_damping_ratio * damping_coefficient};
  }

  ContactResponse respond(double delta, double vn, double r_eff, double m_eff) const {
    return {force(delta, vn, r_eff, m_eff), tangential(delta, r_eff, m_eff)};
  }

  double elastic_energy(double delta, double /*r_eff*/) const {
    return 0.5 * stiffness * delta * delta;
  }

  /// Contact duration (s) of a pair of effective mass m_eff (kg): the overlap's half period.
  double contact_duration(double m_eff) const {
    const double g = damping_coefficient / (2.0 * m_eff);
    return std::numbers::pi / std::sqrt(stiffness / m_eff - g * g);
  }
  /// Restitution of a pair of effective mass m_eff: exp(-gamma t_c / (2 m*)).
  double restitution(double m_eff) const {
    return std::exp(-damping_coefficient * contact_duration(m_eff) / (2.0 * m_eff));
  }
};

}  // namespace drumlab
