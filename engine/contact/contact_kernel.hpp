#pragma once
// The force of one contact, and batches that evaluate it on many contacts at once.
//
// A contact's force is a chain of square roots and divisions (distance, normal, Hertz stiffness,
// damping, history rotation, Coulomb limit); one contact at a time, each waits for the last, and
// the kernel took about half the step (measured by evaluating it twice). The batches gather up to
// kSize contacts into arrays of each input (structure of arrays) and run the kernel in a loop the
// compiler turns into SIMD code (4 contacts per instruction with AVX2), which is why the laws are
// written without branches (selects instead). Every contact is computed by the vector loop, its
// count padded to a multiple of kLanes, so a contact's result does not depend on where in a batch
// it falls: the same bits for any number of threads.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "engine/contact/contact_model.hpp"
#include "engine/contact/lane_gather.hpp"
#include "engine/contact/lane_vec.hpp"
#include "engine/periodic.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// One contact at one instant. n: unit normal towards i; delta: overlap; a_i, a_j: branch lengths
/// from the centres to the contact point (0 on a wall's side); stop_rate: see RollingResistance;
/// inv_dist: 1 / |x_i - x_j| (0 at a wall; RollingSpring's objective correction).
struct ContactGeometry {
  LaneVec n;
  double delta;
  double r_eff;
  double m_eff;
  double a_i;
  double a_j;
  double stop_rate;
  double inv_dist;
};

/// Force on i and torques on i and j of one contact.
struct ContactOutput {
  LaneVec force;
  LaneVec torque_i;
  LaneVec torque_j;
};

/// Force of one contact, shared by the pair and the wall loop. v: velocity of i relative to the
/// other body's surface, without the spins w_i, w_j; xi: the contact's tangential history,
/// incremented over history_dt; xi_r: its rolling spring (RollingKind::spring only), likewise.
template <class Normal, bool Tangential, RollingKind Rolling>
[[gnu::always_inline]] inline ContactOutput contact_response(const ContactLaw<Normal>& law,
                                                             const ContactGeometry& g, LaneVec v,
                                                             const LaneVec& w_i, const LaneVec& w_j,
                                                             LaneVec& xi, LaneVec& xi_r,
                                                             double history_dt) {
  const LaneVec v_centres = v;
  if constexpr (Tangential) v -= (g.a_i * w_i + g.a_j * w_j).cross(g.n);
  const double vn = v.dot(g.n);
  ContactOutput out;
  double fn = 0.0;
  if constexpr (Tangential) {
    const ContactResponse r = law.normal.respond(g.delta, vn, g.r_eff, g.m_eff);
    fn = r.normal_force;
    const LaneVec vt = v - vn * g.n;
    const LaneVec ft = law.tangential.force(xi, g.n, vt, r.tangential, std::abs(fn), history_dt);
    const LaneVec nxft = g.n.cross(ft);
    out.force = fn * g.n + ft;
    out.torque_i = -g.a_i * nxft;
    out.torque_j = -g.a_j * nxft;
  } else {
    fn = law.normal.force(g.delta, vn, g.r_eff, g.m_eff);
    out.force = fn * g.n;
  }
  if constexpr (Rolling == RollingKind::torque) {
    const LaneVec m = law.rolling.torque(w_i - w_j, std::abs(fn), g.r_eff, g.stop_rate);
    out.torque_i += m;
    out.torque_j -= m;
  } else if constexpr (Rolling == RollingKind::spring) {
    const LaneVec m = law.rolling_spring.torque(xi_r, g.n, w_i - w_j, v_centres, g.inv_dist,
                                                g.r_eff, std::abs(fn), history_dt);
    out.torque_i += m;
    out.torque_j -= m;
  }
  return out;
}

/// kSize values of each component of a vector, one per contact.
template <std::size_t kSize>
struct Lanes3 {
  alignas(64) double x[kSize];
  alignas(64) double y[kSize];
  alignas(64) double z[kSize];

  [[gnu::always_inline]] LaneVec get(std::size_t l) const { return {x[l], y[l], z[l]}; }
  [[gnu::always_inline]] Vec3 vec3(std::size_t l) const { return {x[l], y[l], z[l]}; }
  [[gnu::always_inline]] void set(std::size_t l, const LaneVec& v) {
    x[l] = v.x;
    y[l] = v.y;
    z[l] = v.z;
  }
  [[gnu::always_inline]] void set(std::size_t l, const Vec3& v) {
    x[l] = v.x();
    y[l] = v.y();
    z[l] = v.z();
  }
};

/// Lanes per SIMD loop iteration that every batch is padded to (8 doubles: AVX-512; AVX2 and SSE2
/// divide it).
inline constexpr std::size_t kLanes = 8;

/// Copies the last filled lane of `batch` into the lanes after it, up to a multiple of kLanes
/// (their results are discarded), so that every contact goes through the vector loop and not a
/// scalar remainder loop; returns that multiple.
template <class Batch>
std::size_t pad_lanes(Batch& batch) {
  const std::size_t n = std::min(Batch::kSize, (batch.count + kLanes - 1) / kLanes * kLanes);
  for (std::size_t l = batch.count; l < n; ++l) batch.copy_lane(batch.count - 1, l);
  return n;
}

/// Up to kSize particle pairs: their inputs, then (after evaluate) their force, torques and
/// advanced history. add() gathers a pair's state; evaluate() runs the kernel on all of them.
struct PairBatch {
  static constexpr std::size_t kSize = 64;
  std::size_t count = 0;
  std::size_t k[kSize];  ///< the caller's contact index of each lane
  Index i[kSize];
  Index j[kSize];
  Lanes3<kSize> d;  ///< separation x_i - x_j
  alignas(64) double r_i[kSize];
  alignas(64) double r_j[kSize];
  alignas(64) double inv_mass_sum[kSize];
  alignas(64) double inv_inertia_sum[kSize];
  Lanes3<kSize> v;  ///< v_i - v_j
  Lanes3<kSize> w_i;
  Lanes3<kSize> w_j;
  Lanes3<kSize> xi;    ///< history: in, then advanced
  Lanes3<kSize> xi_r;  ///< rolling spring (RollingKind::spring): in (set_rolling), then advanced
  Lanes3<kSize> force;
  Lanes3<kSize> torque_i;
  Lanes3<kSize> torque_j;

  bool full() const { return count == kSize; }

  /// The rolling spring of the pair add() gathered last (RollingKind::spring).
  [[gnu::always_inline]] void set_rolling(const double* xr) {
    xi_r.set(count - 1, LaneVec{xr[0], xr[1], xr[2]});
  }

  /// Adds the overlapping pair (i, j) at separation d (0 < |d| < r_i + r_j), history xi, as
  /// contact k.
  [[gnu::always_inline]] void add(const Particles& p, std::size_t pi, Index pj, const Vec3& dij,
                                  const Vec3& history, std::size_t contact) {
    const std::size_t l = count++;
    k[l] = contact;
    i[l] = static_cast<Index>(pi);
    j[l] = pj;
    fill_lane(l, p, pi, pj, dij, history);
  }

  /// Adds the overlapping pair (i, j) as contact k, by its indices alone: gather() reads its
  /// state (what add() takes) for every lane so added, before evaluate().
  [[gnu::always_inline]] void add_index(std::size_t pi, Index pj, std::size_t contact) {
    const std::size_t l = count++;
    k[l] = contact;
    i[l] = static_cast<Index>(pi);
    j[l] = pj;
  }

  /// The state add() takes, of every lane add_index() added: separation (nearest image for a
  /// period > 0), radii, inverse mass and inertia sums, velocities, spins, and the history
  /// history[k]. The same values as add(): four lanes at a time in registers where the build has
  /// AVX2 (lane_gather.hpp).
  void gather(const Particles& p, const Vec3* history, double period) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double));
#if defined(__AVX2__)
    const std::size_t n = (count + 3) / 4 * 4;
    for (std::size_t l = count; l < n; ++l) {  // lanes pad_lanes overwrites: any valid index
      k[l] = k[count - 1];
      i[l] = i[count - 1];
      j[l] = j[count - 1];
    }
    const auto* pos = reinterpret_cast<const double*>(p.position.data());
    const auto* vel = reinterpret_cast<const double*>(p.velocity.data());
    const auto* spin = reinterpret_cast<const double*>(p.omega.data());
    const auto* hist = reinterpret_cast<const double*>(history);
    // Three passes (the row particle's state, the partner's, the history), so that each
    // keeps its four lanes' offsets in registers.
    for (std::size_t l = 0; l < n; l += 4) {
      const std::size_t a[4] = {i[l], i[l + 1], i[l + 2], i[l + 3]};
      const std::size_t a3[4] = {3 * a[0], 3 * a[1], 3 * a[2], 3 * a[3]};
      store_lanes3(load_lanes3(pos, a3), d.x + l, d.y + l, d.z + l);
      store_lanes3(load_lanes3(vel, a3), v.x + l, v.y + l, v.z + l);
      store_lanes3(load_lanes3(spin, a3), w_i.x + l, w_i.y + l, w_i.z + l);
      _mm256_store_pd(r_i + l, load_lanes1(p.radius.data(), a));
      _mm256_store_pd(inv_mass_sum + l, load_lanes1(p.inv_mass.data(), a));
      _mm256_store_pd(inv_inertia_sum + l, load_lanes1(p.inv_inertia.data(), a));
    }
    for (std::size_t l = 0; l < n; l += 4) {
      const std::size_t b[4] = {j[l], j[l + 1], j[l + 2], j[l + 3]};
      const std::size_t b3[4] = {3 * b[0], 3 * b[1], 3 * b[2], 3 * b[3]};
      const Lanes4x3 xj = load_lanes3(pos, b3);
      Lanes4x3 dl{_mm256_sub_pd(_mm256_load_pd(d.x + l), xj.x),
                  _mm256_sub_pd(_mm256_load_pd(d.y + l), xj.y),
                  _mm256_sub_pd(_mm256_load_pd(d.z + l), xj.z)};
      if (period > 0.0) dl.z = nearest_image_z4(dl.z, period);
      store_lanes3(dl, d.x + l, d.y + l, d.z + l);
      const Lanes4x3 vj = load_lanes3(vel, b3);
      _mm256_store_pd(v.x + l, _mm256_sub_pd(_mm256_load_pd(v.x + l), vj.x));
      _mm256_store_pd(v.y + l, _mm256_sub_pd(_mm256_load_pd(v.y + l), vj.y));
      _mm256_store_pd(v.z + l, _mm256_sub_pd(_mm256_load_pd(v.z + l), vj.z));
      store_lanes3(load_lanes3(spin, b3), w_j.x + l, w_j.y + l, w_j.z + l);
      _mm256_store_pd(r_j + l, load_lanes1(p.radius.data(), b));
      _mm256_store_pd(inv_mass_sum + l, _mm256_add_pd(_mm256_load_pd(inv_mass_sum + l),
                                                      load_lanes1(p.inv_mass.data(), b)));
      _mm256_store_pd(inv_inertia_sum + l, _mm256_add_pd(_mm256_load_pd(inv_inertia_sum + l),
                                                         load_lanes1(p.inv_inertia.data(), b)));
    }
    for (std::size_t l = 0; l < n; l += 4) {
      const std::size_t c3[4] = {3 * k[l], 3 * k[l + 1], 3 * k[l + 2], 3 * k[l + 3]};
      store_lanes3(load_lanes3(hist, c3), xi.x + l, xi.y + l, xi.z + l);
    }
#else
    for (std::size_t l = 0; l < count; ++l) {
      fill_lane(l, p, i[l], j[l], nearest_image(p.position[i[l]], p.position[j[l]], period),
                history[k[l]]);
    }
#endif
  }

  /// Computes force, torques and the advanced history xi (and xi_r) of every lane.
  template <class Normal, bool Tangential, RollingKind Rolling>
  void evaluate(const ContactLaw<Normal>& law, double dt, double history_dt) {
    const std::size_t n = pad_lanes(*this);
    for (std::size_t l = 0; l < n; ++l) {
      const LaneVec dl = d.get(l);
      const double sum_r = r_i[l] + r_j[l];
      const double dist = std::sqrt(dl.squaredNorm());
      const double delta = sum_r - dist;
      // One division for R* = r_i r_j / (r_i + r_j) and m* = 1 / (1/m_i + 1/m_j) together:
      // divisions and square roots bound this loop (see the roofline in app/bench/README.md).
      const double inv = 1.0 / (sum_r * inv_mass_sum[l]);
      const double inv_dist = 1.0 / dist;
      const ContactGeometry g{dl * inv_dist,
                              delta,
                              r_i[l] * r_j[l] * inv_mass_sum[l] * inv,
                              sum_r * inv,
                              r_i[l] - 0.5 * delta,
                              r_j[l] - 0.5 * delta,
                              dt * inv_inertia_sum[l],
                              inv_dist};
      LaneVec x = xi.get(l);
      LaneVec x_r;
      if constexpr (Rolling == RollingKind::spring) x_r = xi_r.get(l);
      const ContactOutput o = contact_response<Normal, Tangential, Rolling>(
          law, g, v.get(l), w_i.get(l), w_j.get(l), x, x_r, history_dt);
      xi.set(l, x);
      if constexpr (Rolling == RollingKind::spring) xi_r.set(l, x_r);
      force.set(l, o.force);
      torque_i.set(l, o.torque_i);
      torque_j.set(l, o.torque_j);
    }
  }

 private:
  // Lane l's state from particles pi, pj at separation dij, history `history` (add, gather).
  [[gnu::always_inline]] void fill_lane(std::size_t l, const Particles& p, std::size_t pi, Index pj,
                                        const Vec3& dij, const Vec3& history) {
    d.set(l, dij);
    r_i[l] = p.radius[pi];
    r_j[l] = p.radius[pj];
    inv_mass_sum[l] = p.inv_mass[pi] + p.inv_mass[pj];
    inv_inertia_sum[l] = p.inv_inertia[pi] + p.inv_inertia[pj];
    v.set(l, p.velocity[pi] - p.velocity[pj]);
    w_i.set(l, p.omega[pi]);
    w_j.set(l, p.omega[pj]);
    xi.set(l, history);
  }

  friend std::size_t pad_lanes<PairBatch>(PairBatch&);
  void copy_lane(std::size_t from, std::size_t to) {
    d.set(to, d.get(from));
    r_i[to] = r_i[from];
    r_j[to] = r_j[from];
    inv_mass_sum[to] = inv_mass_sum[from];
    inv_inertia_sum[to] = inv_inertia_sum[from];
    v.set(to, v.get(from));
    w_i.set(to, w_i.get(from));
    w_j.set(to, w_j.get(from));
    xi.set(to, xi.get(from));
    xi_r.set(to, xi_r.get(from));
  }
};

/// Up to kSize particle-wall contacts, their geometry given (drum.contact); as PairBatch.
struct WallBatch {
  static constexpr std::size_t kSize = 32;
  std::size_t count = 0;
  Index i[kSize];
  std::size_t part[kSize];
  Lanes3<kSize> n;
  alignas(64) double delta[kSize];
  alignas(64) double radius[kSize];
  alignas(64) double mass[kSize];
  alignas(64) double stop_rate[kSize];
  Lanes3<kSize> v;  ///< v_i - wall surface velocity at the contact point
  Lanes3<kSize> w_i;
  Lanes3<kSize> xi;
  Lanes3<kSize> xi_r;  ///< rolling spring (RollingKind::spring): in (set_rolling), then advanced
  Lanes3<kSize> force;
  Lanes3<kSize> torque_i;

  bool full() const { return count == kSize; }

  /// The rolling spring of the contact add() gathered last (RollingKind::spring).
  void set_rolling(const Vec3& xr) { xi_r.set(count - 1, xr); }

  void add(Index pi, std::size_t wall_part, const Vec3& normal, double overlap, double r, double m,
           double stop, const Vec3& v_rel, const Vec3& w, const Vec3& history) {
    const std::size_t l = count++;
    i[l] = pi;
    part[l] = wall_part;
    n.set(l, normal);
    delta[l] = overlap;
    radius[l] = r;
    mass[l] = m;
    stop_rate[l] = stop;
    v.set(l, v_rel);
    w_i.set(l, w);
    xi.set(l, history);
  }

  /// As PairBatch::evaluate; wall_spin: the wall's angular velocity.
  template <class Normal, bool Tangential, RollingKind Rolling>
  void evaluate(const ContactLaw<Normal>& law, const Vec3& wall_spin, double history_dt) {
    const std::size_t cnt = pad_lanes(*this);
    const LaneVec spin{wall_spin.x(), wall_spin.y(), wall_spin.z()};
    for (std::size_t l = 0; l < cnt; ++l) {
      const ContactGeometry g{
          n.get(l), delta[l],     radius[l], mass[l], radius[l] - 0.5 * delta[l],
          0.0,      stop_rate[l], 0.0};
      LaneVec x = xi.get(l);
      LaneVec x_r;
      if constexpr (Rolling == RollingKind::spring) x_r = xi_r.get(l);
      const ContactOutput o = contact_response<Normal, Tangential, Rolling>(
          law, g, v.get(l), w_i.get(l), spin, x, x_r, history_dt);
      xi.set(l, x);
      if constexpr (Rolling == RollingKind::spring) xi_r.set(l, x_r);
      force.set(l, o.force);
      torque_i.set(l, o.torque_i);
    }
  }

 private:
  friend std::size_t pad_lanes<WallBatch>(WallBatch&);
  void copy_lane(std::size_t from, std::size_t to) {
    n.set(to, n.get(from));
    delta[to] = delta[from];
    radius[to] = radius[from];
    mass[to] = mass[from];
    stop_rate[to] = stop_rate[from];
    v.set(to, v.get(from));
    w_i.set(to, w_i.get(from));
    xi.set(to, xi.get(from));
    xi_r.set(to, xi_r.get(from));
  }
};

}  // namespace drumlab
