#include "engine/contact/contact_model.hpp"

#include <cmath>

#include <fmt/format.h>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace drumlab {
namespace {

void check_material(const Material& m, const char* what) {
  if (!(m.youngs_modulus > 0.0) || !std::isfinite(m.youngs_modulus)) {
    throw InputError(
        fmt::format("{}.youngs_modulus must be positive, got {}", what, m.youngs_modulus));
  }
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5)) {
    throw InputError(
        fmt::format("{}.poisson_ratio must be in (-1, 0.5), got {}", what, m.poisson_ratio));
  }
  if (!(m.restitution > 0.0 && m.restitution <= 1.0)) {
    throw InputError(fmt::format("{}.restitution must be in (0, 1], got {}", what, m.restitution));
  }
  if (!(m.friction >= 0.0) || !(m.rolling_friction >= 0.0)) {
    throw InputError(fmt::format("{}: friction and rolling_friction must be >= 0", what));
  }
}

// One contact at one instant. n: unit normal towards i; delta: overlap; a_i, a_j: branch lengths
// from the centres to the contact point (0 on a wall's side); stop_rate: see RollingResistance.
struct ContactGeometry {
  Vec3 n;
  double delta;
  double r_eff;
  double m_eff;
  double a_i;
  double a_j;
  double stop_rate;
};

// Force of one contact, shared by the pair and the wall loop. v: velocity of i relative to the
// other body's surface, without the spins w_i, w_j; xi: the contact's tangential history,
// incremented over history_dt. Returns the force on i and adds the torques to t_i and, for a
// pair, *t_j (null for a wall).
template <class Normal, bool Tangential, bool Rolling>
struct ContactKernel {
  const ContactLaw<Normal>& law;

  [[gnu::always_inline]] inline Vec3 operator()(const ContactGeometry& g, Vec3 v, const Vec3& w_i,
                                                const Vec3& w_j, Vec3& xi, double history_dt,
                                                Vec3& t_i, Vec3* t_j) const {
    if constexpr (Tangential) v -= (g.a_i * w_i + g.a_j * w_j).cross(g.n);
    const double vn = v.dot(g.n);
    double fn = 0.0;
    TangentialCoefficients c;
    if constexpr (Tangential) {
      const ContactResponse r = law.normal.respond(g.delta, vn, g.r_eff, g.m_eff);
      fn = r.normal_force;
      c = r.tangential;
    } else {
      fn = law.normal.force(g.delta, vn, g.r_eff, g.m_eff);
    }
    Vec3 f = fn * g.n;
    if constexpr (Tangential) {
      const Vec3 vt = v - vn * g.n;
      const Vec3 ft = law.tangential.force(xi, g.n, vt, c, std::abs(fn), history_dt);
      f += ft;
      const Vec3 nxft = g.n.cross(ft);
      t_i -= g.a_i * nxft;
      if (t_j) *t_j -= g.a_j * nxft;
    }
    if constexpr (Rolling) {
      const Vec3 m = law.rolling.torque(w_i - w_j, std::abs(fn), g.r_eff, g.stop_rate);
      t_i += m;
      if (t_j) *t_j -= m;
    }
    return f;
  }
};

// Separation of i from j (m); with period > 0 the nearest image along z.
[[gnu::always_inline]] inline Vec3 separation(const Particles& p, std::size_t i, Index j,
                                              double period) {
  Vec3 d = p.position[i] - p.position[j];
  if (period > 0.0) {
    if (d.z() > 0.5 * period) d.z() -= period;
    if (d.z() < -0.5 * period) d.z() += period;
  }
  return d;
}

// Geometry of the overlapping pair (i, j) at separation d (0 < |d| < r_i + r_j).
[[gnu::always_inline]] inline ContactGeometry overlap_geometry(const Particles& p, std::size_t i,
                                                               Index j, const Vec3& d, double dt) {
  const double sum_r = p.radius[i] + p.radius[j];
  const double dist = std::sqrt(d.squaredNorm());
  const double delta = sum_r - dist;
  return ContactGeometry{d / dist,
                         delta,
                         p.radius[i] * p.radius[j] / sum_r,
                         1.0 / (p.inv_mass[i] + p.inv_mass[j]),
                         p.radius[i] - 0.5 * delta,
                         p.radius[j] - 0.5 * delta,
                         dt * (p.inv_inertia[i] + p.inv_inertia[j])};
}

// Geometry of contact k = (i, j); false if the spheres do not overlap. `touching` counts the
// pairs within the search's touching tolerance (the pairs a search with margin 0 finds).
inline bool pair_geometry(const Particles& p, std::size_t i, Index j, double period, double dt,
                          ContactGeometry& g, std::size_t& touching) {
  const Vec3 d = separation(p, i, j, period);
  const double sum_r = p.radius[i] + p.radius[j];
  const double dist2 = d.squaredNorm();
  if (dist2 >= sum_r * sum_r || dist2 == 0.0) {
    const double cut = sum_r + kTouchTolerance;
    if (dist2 <= cut * cut) ++touching;
    return false;
  }
  ++touching;
  g = overlap_geometry(p, i, j, d, dt);
  return true;
}

// Force on i and torques on i and j of the overlapping pair k = (i, j), advancing its history xi.
struct PairContribution {
  Vec3 force = Vec3::Zero();
  Vec3 torque_i = Vec3::Zero();
  Vec3 torque_j = Vec3::Zero();
};

template <class Kernel>
[[gnu::always_inline]] inline PairContribution pair_contribution(const Kernel& kernel,
                                                                 const Particles& p, std::size_t i,
                                                                 Index j, Vec3& xi, double period,
                                                                 double dt, double history_dt) {
  const ContactGeometry g = overlap_geometry(p, i, j, separation(p, i, j, period), dt);
  PairContribution c;
  c.force = kernel(g, p.velocity[i] - p.velocity[j], p.omega[i], p.omega[j], xi, history_dt,
                   c.torque_i, &c.torque_j);
  return c;
}

// Visits the entries k in [begin, end) of row i: apart(k) for those that do not overlap (in any
// order), then overlap(k) for those that do, by increasing k. Most entries of a Verlet list do not
// overlap, in no predictable pattern; so each chunk is first split by a loop without branches,
// the overlapping entries from the front of `sel`, the others from its back, and the force
// kernel then runs without a mispredicted branch per entry (measured +10 % p-steps/s).
// `touching` counts the entries within the touching tolerance, as pair_geometry does.
template <class Overlap, class Apart>
[[gnu::always_inline]] inline void split_row(const Particles& p, std::span<const Index> col,
                                             std::size_t i, std::size_t begin, std::size_t end,
                                             double period, std::size_t& touching,
                                             Overlap&& overlap, Apart&& apart) {
  constexpr std::size_t kChunk = 64;
  std::uint32_t sel[kChunk];
  const double r_i = p.radius[i];
  for (std::size_t k0 = begin; k0 < end; k0 += kChunk) {
    const std::size_t k1 = std::min(end, k0 + kChunk);
    std::size_t front = 0, back = k1 - k0;  // sel[0, front): overlapping; sel[back, n): apart
    for (std::size_t k = k0; k < k1; ++k) {
      const Index j = col[k];
      const Vec3 d = separation(p, i, j, period);
      const double sum_r = r_i + p.radius[j];
      const double dist2 = d.squaredNorm();
      const double cut = sum_r + kTouchTolerance;
      const auto overlapping = static_cast<std::size_t>((dist2 < sum_r * sum_r) & (dist2 != 0.0));
      touching += static_cast<std::size_t>(dist2 <= cut * cut);
      const auto entry = static_cast<std::uint32_t>(k - k0);
      sel[front] = entry;
      sel[back - 1] = entry;  // if overlapping, a free slot, claimed later from either end
      front += overlapping;
      back -= 1 - overlapping;
    }
    for (std::size_t q = back; q < k1 - k0; ++q) apart(k0 + sel[q]);
    for (std::size_t q = 0; q < front; ++q) overlap(k0 + sel[q]);
  }
}

// One thread: accumulate directly. Every particle receives its contributions in the order the
// two-pass loop below sums them (rows where it is the partner by k, then its own row by k), each
// contact's torques first summed from zero, so both give bit-identical results.
template <class Normal, bool Tangential, bool Rolling>
std::size_t pair_loop_serial(const ContactLaw<Normal>& law, Particles& p, ContactList& contacts,
                             double period, double dt, double history_dt) {
  const ContactKernel<Normal, Tangential, Rolling> kernel{law};
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto hist = contacts.history();
  std::size_t touching = 0;
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    split_row(
        p, col, i, row[i], row[i + 1], period, touching,
        [&](std::size_t k) {
          const Index j = col[k];
          const PairContribution c =
              pair_contribution(kernel, p, i, j, hist[k], period, dt, history_dt);
          p.force[i] += c.force;
          p.force[j] -= c.force;
          if constexpr (Tangential || Rolling) {
            p.torque[i] += c.torque_i;
            p.torque[j] += c.torque_j;
          }
        },
        [&](std::size_t k) { hist[k].setZero(); });  // no (longer) overlapping: history ends
  }
  return touching;
}

// Pass 1 of the multi-threaded loop over rows [begin, begin + kRowsPerChunk): each contact's
// force and torques into its buffers. Not inlined into the OpenMP region, where the shared
// variables would be read through pointers (callgrind, 20 steps on 2 threads: 265.2 M -> 252.1 M
// instructions in this pass).
constexpr std::size_t kRowsPerChunk = 64;

template <class Kernel, bool kTorque>
[[gnu::noinline]] std::size_t buffer_rows(const Kernel& kernel, const Particles& p,
                                          std::span<const std::size_t> row,
                                          std::span<const Index> col, std::span<Vec3> hist,
                                          PairForceBuffers& buf, std::size_t begin, double period,
                                          double dt, double history_dt) {
  const std::size_t end = std::min(row.size() - 1, begin + kRowsPerChunk);
  std::size_t touching = 0;
  for (std::size_t i = begin; i < end; ++i) {
    split_row(
        p, col, i, row[i], row[i + 1], period, touching,
        [&](std::size_t k) {
          const PairContribution c =
              pair_contribution(kernel, p, i, col[k], hist[k], period, dt, history_dt);
          buf.force[k] = c.force;
          if constexpr (kTorque) {
            buf.torque_i[k] = c.torque_i;
            buf.torque_j[k] = c.torque_j;
          }
        },
        [&](std::size_t k) {
          hist[k].setZero();  // not (or no longer) overlapping: the history ends
          buf.force[k].setZero();
          if constexpr (kTorque) {
            buf.torque_i[k].setZero();
            buf.torque_j[k].setZero();
          }
        });
  }
  return touching;
}

// Several threads: two passes, so the result does not depend on the number of threads: (1) each
// contact's force and torques into per-contact buffers (contacts are independent; each owns its
// history), (2) each particle sums its contacts in a fixed order: the rows where it is the
// partner, by k, then its own row, by k.
template <class Normal, bool Tangential, bool Rolling>
std::size_t pair_loop(const ContactLaw<Normal>& law, Particles& p, ContactList& contacts,
                      PairForceBuffers& buf, double period, double dt, double history_dt) {
#ifdef _OPENMP
  if (omp_get_max_threads() == 1)
#endif
  {
    return pair_loop_serial<Normal, Tangential, Rolling>(law, p, contacts, period, dt, history_dt);
  }
  constexpr bool kTorque = Tangential || Rolling;
  using Kernel = ContactKernel<Normal, Tangential, Rolling>;
  const Kernel kernel{law};
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto hist = contacts.history();
  const auto chunks =
      static_cast<std::int64_t>((contacts.rows() + kRowsPerChunk - 1) / kRowsPerChunk);
  buf.force.resize(contacts.size());
  if constexpr (kTorque) {
    buf.torque_i.resize(contacts.size());
    buf.torque_j.resize(contacts.size());
  }
  const auto rows = static_cast<std::int64_t>(contacts.rows());
  std::size_t touching = 0;
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : touching)
  for (std::int64_t c = 0; c < chunks; ++c) {
    touching += buffer_rows<Kernel, kTorque>(kernel, p, row, col, hist, buf,
                                             static_cast<std::size_t>(c) * kRowsPerChunk, period,
                                             dt, history_dt);
  }
  contacts.index_partners();
  const auto partner_start = contacts.partner_start();
  const auto partner_k = contacts.partner_contacts();
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < rows; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Vec3 f = Vec3::Zero(), t = Vec3::Zero();
    for (std::size_t q = partner_start[i]; q < partner_start[i + 1]; ++q) {
      const std::size_t k = partner_k[q];
      f -= buf.force[k];
      if constexpr (kTorque) t += buf.torque_j[k];
    }
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      f += buf.force[k];
      if constexpr (kTorque) t += buf.torque_i[k];
    }
    p.force[i] += f;
    if constexpr (kTorque) p.torque[i] += t;
  }
  return touching;
}

// The pair loop's force, read-only: history copied (and not advanced), torques discarded.
template <class Normal, bool Tangential, bool Rolling>
void pair_force_loop(const ContactLaw<Normal>& law, const Particles& p, const ContactList& contacts,
                     double period, double dt, std::vector<ContactForce>& out) {
  const ContactKernel<Normal, Tangential, Rolling> kernel{law};
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto hist = contacts.history();
  out.clear();
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const Index j = col[k];
      ContactGeometry g;
      std::size_t touching = 0;
      if (!pair_geometry(p, i, j, period, dt, g, touching)) continue;
      Vec3 xi = hist[k];
      Vec3 t_i = Vec3::Zero();
      Vec3 t_j = Vec3::Zero();
      const Vec3 f =
          kernel(g, p.velocity[i] - p.velocity[j], p.omega[i], p.omega[j], xi, 0.0, t_i, &t_j);
      out.push_back(ContactForce{static_cast<Index>(i), j, f});
    }
  }
}

template <class Normal, bool Tangential, bool Rolling>
void wall_loop(const ContactLaw<Normal>& law, Particles& p, std::span<const Index> candidates,
               const Drum& drum, double omega, WallHistory& history, double dt, double history_dt) {
  const ContactKernel<Normal, Tangential, Rolling> kernel{law};
  const Vec3 wall_spin(0.0, 0.0, omega);
  const std::size_t parts = drum.periodic() ? 1 : kWallParts;
  const auto n = static_cast<std::int64_t>(candidates.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t q = 0; q < n; ++q) {
    const std::size_t i = candidates[static_cast<std::size_t>(q)];
    const Vec3& x = p.position[i];
    const double r = p.radius[i];
    for (std::size_t part = 0; part < parts; ++part) {
      const WallContact c = drum.contact(static_cast<WallPart>(part), x, r);
      Vec3& xi = history[i][part];
      if (c.overlap <= 0.0) {
        xi.setZero();
        continue;
      }
      const double a = r - 0.5 * c.overlap;
      const Vec3 point = x - a * c.normal;
      const ContactGeometry g{c.normal, c.overlap, r, p.mass[i], a, 0.0, dt * p.inv_inertia[i]};
      // The wall's spin enters through its surface velocity (branch length 0 on its side) and
      // through the relative rotation rate seen by rolling resistance.
      const Vec3 f = kernel(g, p.velocity[i] - Drum::wall_velocity(point, omega), p.omega[i],
                            wall_spin, xi, history_dt, p.torque[i], nullptr);
      p.force[i] += f;
    }
  }
}

template <class Normal>
ContactLaw<Normal> make_law(const Normal& n, const MindlinTangential& t,
                            const RollingResistance& r) {
  return {n, t, r};
}

NormalVariant make_normal(const SceneConfig& s, const Material& other, double restitution) {
  if (s.contact.normal == NormalLaw::linear) {
    if (!(s.contact.linear_stiffness > 0.0) || !std::isfinite(s.contact.linear_stiffness)) {
      throw InputError(
          fmt::format("contact.linear_stiffness must be positive for the linear law, "
                      "got {}",
                      s.contact.linear_stiffness));
    }
    return LinearSpringDashpot(s.contact.linear_stiffness, restitution);
  }
  return HertzNormal(effective_youngs_modulus(s.material, other),
                     effective_shear_modulus(s.material, other), restitution);
}

// Calls loop.template operator()<Normal, Tangential, Rolling>(law) with the scene's runtime
// choices turned into template arguments, so the chosen law inlines into the loop.
template <class Parts, class Loop>
void with_law(const Parts& parts, bool tangential, bool rolling, Loop&& loop) {
  std::visit(
      [&](const auto& normal) {
        const auto law = make_law(normal, parts.tangential, parts.rolling);
        using N = std::decay_t<decltype(normal)>;
        if (tangential && rolling) {
          loop.template operator()<N, true, true>(law);
        } else if (tangential) {
          loop.template operator()<N, true, false>(law);
        } else if (rolling) {
          loop.template operator()<N, false, true>(law);
        } else {
          loop.template operator()<N, false, false>(law);
        }
      },
      parts.normal);
}

}  // namespace

ContactModel::ContactModel(const SceneConfig& scene) {
  check_material(scene.material, "material");
  check_material(scene.wall, "wall");
  pair_ = {make_normal(scene, scene.material, scene.material.restitution),
           MindlinTangential{scene.material.friction},
           RollingResistance{scene.material.rolling_friction}};
  wall_ = {make_normal(scene, scene.wall, scene.wall.restitution),
           MindlinTangential{scene.wall.friction}, RollingResistance{scene.wall.rolling_friction}};
  pair_tangential_ = scene.material.friction > 0.0;
  pair_rolling_ = scene.material.rolling_friction > 0.0;
  wall_tangential_ = scene.wall.friction > 0.0;
  wall_rolling_ = scene.wall.rolling_friction > 0.0;
}

std::size_t ContactModel::add_pair_forces(Particles& p, ContactList& contacts,
                                          PairForceBuffers& buffers, double period, double dt,
                                          double history_dt) const {
  std::size_t touching = 0;
  with_law(pair_, pair_tangential_, pair_rolling_,
           [&]<class N, bool Tangential, bool Rolling>(const ContactLaw<N>& law) {
             touching = pair_loop<N, Tangential, Rolling>(law, p, contacts, buffers, period, dt,
                                                          history_dt);
           });
  return touching;
}

void ContactModel::add_wall_forces(Particles& p, std::span<const Index> candidates,
                                   const Drum& drum, double omega, WallHistory& history, double dt,
                                   double history_dt) const {
  with_law(wall_, wall_tangential_, wall_rolling_,
           [&]<class N, bool Tangential, bool Rolling>(const ContactLaw<N>& law) {
             wall_loop<N, Tangential, Rolling>(law, p, candidates, drum, omega, history, dt,
                                               history_dt);
           });
}

void ContactModel::pair_forces(const Particles& p, const ContactList& contacts, double period,
                               double dt, std::vector<ContactForce>& out) const {
  std::visit(
      [&](const auto& normal) {
        const auto law = make_law(normal, pair_.tangential, pair_.rolling);
        using N = std::decay_t<decltype(normal)>;
        if (pair_tangential_) {
          pair_force_loop<N, true, false>(law, p, contacts, period, dt, out);
        } else {
          pair_force_loop<N, false, false>(law, p, contacts, period, dt, out);
        }
      },
      pair_.normal);
}

double ContactModel::pair_elastic_energy(double delta, double r_eff) const {
  return std::visit([&](const auto& n) { return n.elastic_energy(delta, r_eff); }, pair_.normal);
}

double ContactModel::wall_elastic_energy(double delta, double r) const {
  return std::visit([&](const auto& n) { return n.elastic_energy(delta, r); }, wall_.normal);
}

}  // namespace drumlab
