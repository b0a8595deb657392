#pragma once
// Linear spring-dashpot normal contact:
//     F_n = k delta - gamma v_n,   gamma = 2 sqrt(m* k) (-ln e) / sqrt(pi^2 + ln^2 e),
// (v_n = (v_i - v_j) . n, negative while approaching). This is a damped harmonic oscillator in the
// overlap, so a contact that ends when the overlap returns to zero has restitution exactly e and
// duration t_c = pi / sqrt(k/m* - (gamma / (2 m*))^2). The exactness needs the attractive force the
// dashpot gives near separation: the force is deliberately NOT clipped at zero.
//
// Tangential spring (when friction is used): k_t = 2/7 k, which gives the tangential oscillation
// of a sphere the same period as the normal one, with gamma_t from the same damping ratio.
#include <cmath>
#include <numbers>

#include "engine/contact/hertz_mindlin.hpp"

namespace drumlab {

struct LinearSpringDashpot {
  double stiffness = 0.0;      ///< k, N/m
  double damping_ratio = 0.0;  ///< zeta = (-ln e) / sqrt(pi^2 + ln^2 e)

  LinearSpringDashpot() = default;
  LinearSpringDashpot(double k, double restitution) : stiffness(k) {
    const double l = std::log(restitution);
    damping_ratio = -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
  }

  /// gamma (kg/s) for effective mass m_eff.
  double damping(double m_eff) const { return 2.0 * std::sqrt(m_eff * stiffness) * damping_ratio; }

  /// Normal force along n (N), positive repulsive; see the file comment.
  double force(double delta, double vn, double /*r_eff*/, double m_eff) const {
    return stiffness * delta - damping(m_eff) * vn;
  }

  TangentialCoefficients tangential(double /*delta*/, double /*r_eff*/, double m_eff) const {
    const double k_t = (2.0 / 7.0) * stiffness;
    return {k_t, 2.0 * std::sqrt(m_eff * k_t) * damping_ratio};
  }

  ContactResponse respond(double delta, double vn, double r_eff, double m_eff) const {
    return {force(delta, vn, r_eff, m_eff), tangential(delta, r_eff, m_eff)};
  }

  double elastic_energy(double delta, double /*r_eff*/) const {
    return 0.5 * stiffness * delta * delta;
  }

  /// Exact contact duration (s): pi / sqrt(k/m* - (gamma/(2 m*))^2).
  double contact_duration(double m_eff) const {
    const double g = damping(m_eff) / (2.0 * m_eff);
    return std::numbers::pi / std::sqrt(stiffness / m_eff - g * g);
  }
};

}  // namespace drumlab
