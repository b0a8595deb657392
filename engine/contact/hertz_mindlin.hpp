#pragma once
// Hertz normal contact with restitution-derived viscous damping, and the Mindlin tangential spring
// with history and a Coulomb limit (the LIGGGHTS "hertz/history" model).
//
// Normal force along the unit normal n (from j to i), positive = repulsive:
//     F_n = 4/3 E* sqrt(R*) delta^{3/2} - gamma_n v_n,
//     gamma_n = -2 sqrt(5/6) beta sqrt(S_n m*),   S_n = 2 E* sqrt(R* delta),
//     beta = ln e / sqrt(ln^2 e + pi^2),
// where delta is the overlap and v_n = (v_i - v_j) . n the normal relative velocity (negative while
// approaching). The attractive part the damping can give near separation is not clipped.
//
// Known bias: beta is the damping ratio of the linear spring-dashpot; the factor 2 sqrt(5/6) maps
// it onto the Hertz spring (damping ~ delta^{1/4}, so the restitution is velocity independent). The
// widely reported bias (achieved restitution above the set e) comes from clipping the tensile part
// of F_n, which ends the contact when the force, not the overlap, reaches zero. Measured in
// tests/validation/test_collisions.cpp (two equal spheres, head on):
//   * as implemented here (not clipped), dt = t_c/2000: |e_achieved - e| <= 1.1e-4 for
//     e = 0.3, 0.5, 0.9 (an independent RK4 integration gives < 1e-6): no measurable bias;
//   * at the default dt = 0.2 t_Rayleigh (~10 steps per contact): e = 0.5 -> 0.482 ... 0.498,
//     e = 0.9 -> 0.895 ... 0.902 depending on the impact speed (discretisation, not the law);
//   * with the tensile force clipped: e = 0.1 -> 0.253, 0.5 -> 0.550, 0.9 -> 0.902.
// The damped contact lasts longer than the elastic Hertz time: x1.195 (e = 0.3), x1.093 (e = 0.5),
// x1.011 (e = 0.9).
//
// Tangential (Mindlin, no-slip stiffness): S_t = 8 G* sqrt(R* delta),
//     gamma_t = -2 sqrt(5/6) beta sqrt(S_t m*),
// the tangential displacement xi is kept per contact, rotated into the current tangent plane every
// step (keeping its length), incremented by v_t dt, and F_t = -S_t xi - gamma_t v_t limited to
// |F_t| <= mu |F_n|; when sliding, xi is reset so that the spring and damper give the limit force.
#include <cmath>
#include <numbers>

#include "engine/contact/lane_vec.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// Effective Young's modulus E* (Pa): 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b.
/// For identical materials E* = E / (2 (1 - nu^2)).
inline double effective_youngs_modulus(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
}

/// Effective shear modulus G* (Pa): 1/G* = (2 - nu_a)/G_a + (2 - nu_b)/G_b, G = E / (2 (1 + nu)).
/// For identical materials G* = G / (2 (2 - nu)).
inline double effective_shear_modulus(const Material& a, const Material& b) {
  const double ga = a.youngs_modulus / (2.0 * (1.0 + a.poisson_ratio));
  const double gb = b.youngs_modulus / (2.0 * (1.0 + b.poisson_ratio));
  return 1.0 / ((2.0 - a.poisson_ratio) / ga + (2.0 - b.poisson_ratio) / gb);
}

/// beta = ln e / sqrt(ln^2 e + pi^2), in (-1, 0]; 0 for e = 1 (no damping).
inline double damping_beta(double restitution) {
  const double l = std::log(restitution);
  return l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
}

/// Stiffness (N/m) and damping coefficient (kg/s) of the tangential spring-dashpot of a contact.
struct TangentialCoefficients {
  double stiffness = 0.0;
  double damping = 0.0;
};

/// Normal force and the tangential spring of the same contact, from one evaluation.
struct ContactResponse {
  double normal_force = 0.0;
  TangentialCoefficients tangential;
};

struct HertzNormal {
  double e_star = 0.0;  ///< E*, Pa
  double g_star = 0.0;  ///< G*, Pa
  double beta = 0.0;    ///< from the restitution, see damping_beta

  HertzNormal() = default;
  double tangential_ratio = 0.0;  ///< sqrt(S_t / S_n) = sqrt(4 G* / E*)

  HertzNormal(double e_star_, double g_star_, double restitution)
      : e_star(e_star_),
        g_star(g_star_),
        beta(damping_beta(restitution)),
        tangential_ratio(std::sqrt(4.0 * g_star_ / e_star_)) {}

  /// Normal force along n (N), positive repulsive. delta > 0 overlap (m), vn normal relative
  /// velocity (m/s, negative approaching), r_eff = R* (m), m_eff = m* (kg).
  double force(double delta, double vn, double r_eff, double m_eff) const {
    const double s_n = 2.0 * e_star * std::sqrt(r_eff * delta);
    const double gamma_n = -2.0 * kSqrt56 * beta * std::sqrt(s_n * m_eff);
    return (2.0 / 3.0) * s_n * delta - gamma_n * vn;
  }

  TangentialCoefficients tangential(double delta, double r_eff, double m_eff) const {
    const double s_t = 8.0 * g_star * std::sqrt(r_eff * delta);
    return {s_t, -2.0 * kSqrt56 * beta * std::sqrt(s_t * m_eff)};
  }

  /// force() and tangential() together with two square roots instead of four:
  /// sqrt(S_t m*) = sqrt(S_t / S_n) sqrt(S_n m*) and S_t / S_n = 4 G* / E*.
  [[gnu::always_inline]] ContactResponse respond(double delta, double vn, double r_eff,
                                                 double m_eff) const {
    const double a = std::sqrt(r_eff * delta);
    const double s_n = 2.0 * e_star * a;
    const double damping_n = -2.0 * kSqrt56 * beta * std::sqrt(s_n * m_eff);
    return {(2.0 / 3.0) * s_n * delta - damping_n * vn,
            {8.0 * g_star * a, damping_n * tangential_ratio}};
  }

  /// Energy stored in the Hertz spring (J): 8/15 E* sqrt(R*) delta^{5/2}.
  double elastic_energy(double delta, double r_eff) const {
    return (8.0 / 15.0) * e_star * std::sqrt(r_eff) * delta * delta * std::sqrt(delta);
  }

  /// Hertz contact duration (s) of an elastic head-on impact at relative speed v (m/s):
  /// t_c = 2.868 (m*^2 / (R* E*^2 v))^{1/5}.
  double contact_duration(double r_eff, double m_eff, double v) const {
    return 2.868 * std::pow(m_eff * m_eff / (r_eff * e_star * e_star * v), 0.2);
  }

 private:
  static constexpr double kSqrt56 = 0.91287092917527685576;  // sqrt(5/6)
};

/// Mindlin tangential spring with history and Coulomb limit. The stiffness and damping come from
/// the normal law (HertzNormal::tangential or LinearSpringDashpot::tangential).
struct MindlinTangential {
  double friction = 0.0;  ///< Coulomb mu

  /// Updates the tangential displacement `xi` (m) of one contact and returns the tangential force
  /// on particle i (N). n: unit normal (j -> i); vt: tangential relative velocity of i with
  /// respect to j at the contact point (m/s); fn_abs = |F_n| (N); dt (s).
  [[gnu::always_inline]] Vec3 force(Vec3& xi, const Vec3& n, const Vec3& vt,
                                    const TangentialCoefficients& c, double fn_abs,
                                    double dt) const {
    return force_of<Vec3>(xi, n, vt, c, fn_abs, dt);
  }
  /// The same for the vectorized kernel (contact_kernel.hpp).
  [[gnu::always_inline]] LaneVec force(LaneVec& xi, const LaneVec& n, const LaneVec& vt,
                                       const TangentialCoefficients& c, double fn_abs,
                                       double dt) const {
    return force_of<LaneVec>(xi, n, vt, c, fn_abs, dt);
  }

 private:
  template <class V>
  [[gnu::always_inline]] V force_of(V& xi, const V& n, const V& vt, const TangentialCoefficients& c,
                                    double fn_abs, double dt) const {
    // Rotate the history into the current tangent plane, keeping its length (zero if it was
    // zero or normal to the plane). Written with selects instead of branches, so that a loop over
    // contacts vectorizes (see contact_kernel.hpp); the values not selected may be inf or NaN.
    const double old_len2 = xi.squaredNorm();
    const V in_plane = xi - xi.dot(n) * n;
    const double new_len2 = in_plane.squaredNorm();
    const double rescale = std::sqrt(old_len2 / new_len2);
    const double keep = new_len2 > 1e-24 * old_len2 ? rescale : 0.0;
    xi = in_plane * keep + vt * dt;
    V ft = -c.stiffness * xi - c.damping * vt;
    const double limit = friction * fn_abs;
    const double ft2 = ft.squaredNorm();
    // Sliding: F_t on the Coulomb cone, the spring rescaled to match.
    const bool sliding = ft2 > limit * limit;
    const double cap = limit / std::sqrt(ft2);
    ft *= sliding ? cap : 1.0;
    const V xi_slide = -(ft + c.damping * vt) * (1.0 / c.stiffness);
    const V zero = V::Zero();
    xi = select(sliding, select(c.stiffness > 0.0, xi_slide, zero), xi);
    return ft;
  }
};

}  // namespace drumlab
