#include "engine/contact/contact_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "engine/contact/bridge_batch.hpp"
#include "engine/contact/contact_kernel.hpp"
#include "engine/contact/law_dispatch.hpp"
#include "engine/contact/mesh_wall_history.hpp"
#include "engine/contact/pair_split.hpp"
#include "engine/periodic.hpp"
#include "engine/scene/scene_validation.hpp"
#include "engine/vector_room.hpp"
#ifdef _OPENMP
#include <omp.h>
#endif

namespace drumlab {
namespace {

// Separation of i from j (m); with period > 0 the nearest image along z.
[[gnu::always_inline]] inline Vec3 separation(const Particles& p, std::size_t i, Index j,
                                              double period) {
  return nearest_image(p.position[i], p.position[j], period);
}

// Asks for the cache lines of v's three components (two where it straddles a line's end).
template <int kWrite = 0>
[[gnu::always_inline]] inline void prefetch_vec3(const Vec3* v) {
  const auto* c = reinterpret_cast<const char*>(v);
  __builtin_prefetch(c, kWrite);
  __builtin_prefetch(c + sizeof(Vec3) - 1, kWrite);
}

// Visits the entries k in [begin, end) (rows in order; entry k is row row_of[k]'s), by chunks:
// apart(k0, bits) with bit q set for each entry k0 + q of the chunk that does not overlap, then
// overlap(i, k) for those that do, by increasing k. Most entries of a Verlet list do not overlap,
// in no predictable pattern; so each chunk of 64 is first gathered by a loop without branches (each
// entry's squared distance and radii's sum), split by SIMD compares into a mask of the overlapping
// entries (pair_split.hpp), and the force kernel then runs over the mask's bits without a
// mispredicted branch per entry (measured +10 % p-steps/s against a branch per entry). The chunks
// run across row ends: a row holds ~7 entries, and loops row by row paid three short loops' exits a
// row. `touching` counts the entries within the touching tolerance (what a search with margin 0
// finds). kMark (a scene with cohesive parts): also writes each entry's touch mark (touch_sift.hpp)
// to mark[k], so the cohesive pass need not gather the partners again.
template <bool kMark, class Overlap, class Apart>
[[gnu::always_inline]] inline void split_entries(const Particles& p, std::span<const Index> col,
                                                 std::span<const Index> row_of, std::size_t begin,
                                                 std::size_t end, double period, bool far,
                                                 std::size_t& touching, std::uint8_t* mark,
                                                 Overlap&& overlap, Apart&& apart) {
  constexpr std::size_t kChunk = 64;
  alignas(64) double dist2[kChunk];
  alignas(64) double sum_r[kChunk];
  for (std::size_t k0 = begin; k0 < end; k0 += kChunk) {
    const std::size_t n = std::min(end - k0, kChunk);
    // far: the next chunk's partners asked for now, one chunk (some 10 rows) before the loop
    // below reads them: where the particles do not fit in the caches (the Table 2 drum), these
    // loads were the pair loop's largest stall (app/bench/README.md, "What paid").
    if (far) {
      const std::size_t next = std::min(end, k0 + 2 * kChunk);
      for (std::size_t k = k0 + kChunk; k < next; ++k) {
        prefetch_vec3(p.position.data() + col[k]);
        __builtin_prefetch(p.radius.data() + col[k]);
      }
    }
    for (std::size_t q = 0; q < n; ++q) {
      const Index i = row_of[k0 + q];
      const Index j = col[k0 + q];
      dist2[q] = separation(p, i, j, period).squaredNorm();
      sum_r[q] = p.radius[i] + p.radius[j];
    }
    const PairSplit split =
        split_pairs<kMark>(dist2, sum_r, n, kTouchTolerance, kMark ? mark + k0 : nullptr);
    touching += split.touching;
    apart(k0, first_bits(n) & ~split.overlapping);
    for_each_bit(split.overlapping, [&](std::size_t q) { overlap(row_of[k0 + q], k0 + q); });
  }
}

// From this many particles on, the pair loop also prefetches the partners' positions a chunk
// ahead, their force and torque, and the second line of a 3-vector that straddles two: their
// arrays (144 bytes a particle) then outgrow the caches that the extra instructions cost in (the
// demo drum, 18,825 particles: 0.93-0.98 on one AVX2 core; the deep drum, 75,300: 1.01-1.26
// on two threads; the Table 2 drum: app/bench/README.md, "What paid").
constexpr std::size_t kFarParticles = 32768;

// Evaluates the overlapping entries of rows [begin, end) in batches; for each, by increasing k,
// stores its advanced history and calls sink(batch, l) with its force and torques in lane l (with
// `pull.state`, its live bridge's pull added: TouchingPull). Resets the history of the entries
// that do not overlap. Returns the entries within the touching tolerance.
template <class Normal, bool Tangential, RollingKind Rolling, bool kMark, class Sink>
[[gnu::always_inline]] inline std::size_t batched_rows(const ContactLaw<Normal>& law,
                                                       const Particles& p, ContactList& contacts,
                                                       std::size_t begin, std::size_t end,
                                                       double period, double dt, double history_dt,
                                                       std::uint8_t* mark, const TouchingPull& pull,
                                                       PairBatch& batch, Sink&& sink) {
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto hist = contacts.history();
  // RollingKind::spring: xi_r is the last kRollingStateSize scalars of each contact's state.
  constexpr bool kSpring = Rolling == RollingKind::spring;
  const std::size_t stride = contacts.state_size();
  double* const roll = kSpring ? contacts.state().data() + (stride - kRollingStateSize) : nullptr;
  const auto flush = [&] {
    batch.gather(p, hist.data(), period);
    batch.evaluate<Normal, Tangential, Rolling>(law, dt, history_dt);
    if constexpr (kMark) {
      if (pull.state != nullptr) add_touching_pull(pull, batch);
    }
    for (std::size_t l = 0; l < batch.count; ++l) {
      hist[batch.k[l]] = batch.xi.vec3(l);
      if constexpr (kSpring) {
        double* xr = roll + batch.k[l] * stride;
        xr[0] = batch.xi_r.x[l];
        xr[1] = batch.xi_r.y[l];
        xr[2] = batch.xi_r.z[l];
      }
      sink(batch, l);
    }
    batch.count = 0;
  };
  const bool far = p.size() >= kFarParticles;
  std::size_t touching = 0;
  split_entries<kMark>(
      p, col, contacts.entry_rows(), row[begin], row[end], period, far, touching, mark,
      [&](std::size_t i, std::size_t k) {
        // The partner's state that the split did not read, asked for now: gather() reads it
        // when the batch is full, up to 64 contacts later, and the sink then adds to its force
        // and torque.
        const Index j = col[k];
        if (far) {
          prefetch_vec3(p.velocity.data() + j);
          prefetch_vec3(p.omega.data() + j);
          prefetch_vec3<1>(p.force.data() + j);
          prefetch_vec3<1>(p.torque.data() + j);
        } else {
          __builtin_prefetch(p.velocity.data() + j);
          __builtin_prefetch(p.omega.data() + j);
        }
        __builtin_prefetch(p.inv_mass.data() + j);
        __builtin_prefetch(p.inv_inertia.data() + j);
        batch.add_index(i, j, k);
        if constexpr (kSpring) batch.set_rolling(roll + k * stride);
        if (batch.full()) flush();
      },
      [&](std::size_t k0, std::uint64_t apart) {  // not (or no longer) overlapping
        static_assert(sizeof(Vec3) == 3 * sizeof(double));
        zero_triples(hist[k0].data(), apart);
        if constexpr (kSpring) {
          for_each_bit(apart, [&](std::size_t q) {
            std::fill_n(roll + (k0 + q) * stride, kRollingStateSize, 0.0);
          });
        }
      });
  if (batch.count > 0) flush();
  return touching;
}

// The contributions of one row (particle i's own contacts), summed from zero and added to
// p.force[i], p.torque[i] when the row ends.
template <bool kTorque>
struct RowSum {
  static constexpr std::size_t kNone = ~std::size_t{0};
  std::size_t row = kNone;
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();

  [[gnu::always_inline]] void add(Particles& p, std::size_t i, const PairBatch& b, std::size_t l) {
    if (i != row) finish(p);
    row = i;
    force += b.force.vec3(l);
    if constexpr (kTorque) torque += b.torque_i.vec3(l);
  }
  void finish(Particles& p) {
    if (row == kNone) return;
    p.force[row] += force;
    if constexpr (kTorque) p.torque[row] += torque;
    row = kNone;
    force.setZero();
    torque.setZero();
  }
};

// The order of the sums, the same for any number of threads. Rows are grouped in fixed blocks of
// rows_per_block particles (performance.pair_block_rows). Particle j's force (and torque) is
//     (its shares as the partner of contacts in its own block, by k, from zero
//      + its own row's sum, from zero)
//     + its shares as the partner of contacts from earlier blocks ("cross-block"), by k, from zero.
// A block's rows and partners are all its own, so a thread that takes a whole block adds the first
// two parts straight into the particles; only the cross-block shares (about a fifth to a third of
// the contacts, with particles in Morton order) pass through buffers and a second pass.
// The blocks are ContactList's (index_cross_block): i / rows_per_block in a serial run.
// Receivers of cross-block shares a block of the second pass (BlockDealer).
constexpr std::size_t kReceiverBlock = 1024;

// One thread: the rows in order; the cross-block shares summed per partner in cross_force /
// cross_torque (by k, as the rows come in order) and added at the end.
template <class Normal, bool Tangential, RollingKind Rolling, bool kMark>
std::size_t pair_loop_serial(const ContactLaw<Normal>& law, Particles& p, ContactList& contacts,
                             PairForceBuffers& buf, std::size_t rows_per_block, double period,
                             double dt, double history_dt, const TouchingPull& pull) {
  constexpr bool kTorque = Tangential || rolls(Rolling);
  contacts.index_cross_block(rows_per_block);
  const auto receivers = contacts.cross_receivers();
  const auto block_end = contacts.row_block_end();
  buf.cross_force.resize(p.size());
  if constexpr (kTorque) buf.cross_torque.resize(p.size());
  for (const Index j : receivers) {
    buf.cross_force[j].setZero();
    if constexpr (kTorque) buf.cross_torque[j].setZero();
  }
  PairBatch batch;
  RowSum<kTorque> own;
  const std::size_t touching = batched_rows<Normal, Tangential, Rolling, kMark>(
      law, p, contacts, 0, contacts.rows(), period, dt, history_dt, buf.cohesion.mark.data(), pull,
      batch, [&](const PairBatch& b, std::size_t l) {
        const Index i = b.i[l];
        const Index j = b.j[l];
        own.add(p, i, b, l);
        const bool inner = j < block_end[i];  // one of two addresses (GCC 12 emits a branch)
        Vec3* force = inner ? p.force.data() : buf.cross_force.data();
        force[j] -= b.force.vec3(l);
        if constexpr (kTorque) {
          Vec3* torque = inner ? p.torque.data() : buf.cross_torque.data();
          torque[j] += b.torque_j.vec3(l);
        }
      });
  own.finish(p);
  for (const Index j : receivers) {
    p.force[j] += buf.cross_force[j];
    if constexpr (kTorque) p.torque[j] += buf.cross_torque[j];
  }
  return touching;
}

// Pass 1 of the multi-threaded loop over block `block`: its rows' own sums and its inner partner
// shares straight into the particles (all of the block's alone), and the partner's share (force,
// torque_j) of each overlapping cross-block contact into the next free slot of the block's range
// of slots [row[begin], row[end]), with each listed pair's slot in buf.slot (`zero` for the
// others). Not inlined into the OpenMP region, where the shared variables would be read through
// pointers.
template <class Normal, bool Tangential, RollingKind Rolling, bool kMark>
[[gnu::noinline]] std::size_t block_rows(const ContactLaw<Normal>& law, Particles& p,
                                         ContactList& contacts, PairForceBuffers& buf,
                                         std::size_t block, double period, double dt,
                                         double history_dt, const TouchingPull& pull) {
  constexpr bool kTorque = Tangential || rolls(Rolling);
  const std::size_t begin = contacts.block_start()[block];
  const std::size_t end = contacts.block_start()[block + 1];
  const auto row = contacts.row_start();
  const auto zero = static_cast<std::uint32_t>(contacts.size());
  std::fill(buf.slot.begin() + static_cast<std::ptrdiff_t>(row[begin]),
            buf.slot.begin() + static_cast<std::ptrdiff_t>(row[end]), zero);
  auto next = static_cast<std::uint32_t>(row[begin]);
  PairBatch batch;
  RowSum<kTorque> own;
  const std::size_t touching = batched_rows<Normal, Tangential, Rolling, kMark>(
      law, p, contacts, begin, end, period, dt, history_dt, buf.cohesion.mark.data(), pull, batch,
      [&](const PairBatch& b, std::size_t l) {
        const Index j = b.j[l];
        own.add(p, b.i[l], b, l);
        if (j < end) {
          p.force[j] -= b.force.vec3(l);
          if constexpr (kTorque) p.torque[j] += b.torque_j.vec3(l);
        } else {
          const std::uint32_t s = next++;
          buf.slot[b.k[l]] = s;
          buf.force[s] = b.force.vec3(l);
          if constexpr (kTorque) buf.torque_j[s] = b.torque_j.vec3(l);
        }
      });
  own.finish(p);
  return touching;
}

// Several threads: (1) whole blocks, each by one thread (contacts are independent; each owns its
// history); (2) each particle adds its cross-block shares, by k. kMark: see split_entries (the
// buffer buf.cohesion.mark is sized here).
template <class Normal, bool Tangential, RollingKind Rolling, bool kMark>
std::size_t pair_loop(const ContactLaw<Normal>& law, Particles& p, ContactList& contacts,
                      PairForceBuffers& buf, std::size_t rows_per_block, double period, double dt,
                      double history_dt, const TouchingPull& pull) {
  if constexpr (kMark) resize_with_room(buf.cohesion.mark, contacts.size());
#ifdef _OPENMP
  if (omp_get_max_threads() == 1)
#endif
  {
    return pair_loop_serial<Normal, Tangential, Rolling, kMark>(
        law, p, contacts, buf, rows_per_block, period, dt, history_dt, pull);
  }
  constexpr bool kTorque = Tangential || rolls(Rolling);
  const std::size_t zero = contacts.size();  // the slot of the pairs that do not overlap
  resize_with_room(buf.slot, contacts.size());
  resize_with_room(buf.force, contacts.size() + 1);
  buf.force[zero].setZero();
  if constexpr (kTorque) {
    resize_with_room(buf.torque_j, contacts.size() + 1);
    buf.torque_j[zero].setZero();
  }
  contacts.index_cross_block(rows_per_block);
  const std::size_t blocks = contacts.block_start().size() - 1;
  std::size_t touching = 0;
  // Dealt from both ends of each thread pair's segment (BlockDealer): a block writes only its
  // rows, its inner partners and its own slots, so who takes it does not change the sums.
#pragma omp parallel reduction(+ : touching)
  {
    buf.blocks.deal(blocks);
    for (std::size_t b; buf.blocks.next(b);) {
      touching += block_rows<Normal, Tangential, Rolling, kMark>(law, p, contacts, buf, b, period,
                                                                 dt, history_dt, pull);
    }
  }
  const auto receivers = contacts.cross_receivers();
  const auto start = contacts.cross_start();
  const auto cross_k = contacts.cross_contacts();
#pragma omp parallel
  deal_ranges(buf.blocks, receivers.size(), kReceiverBlock, [&](std::size_t b, std::size_t e) {
    for (std::size_t r = b; r < e; ++r) {
      Vec3 f = Vec3::Zero(), t = Vec3::Zero();
      for (std::size_t q = start[r]; q < start[r + 1]; ++q) {
        const std::uint32_t s = buf.slot[cross_k[q]];
        f -= buf.force[s];
        if constexpr (kTorque) t += buf.torque_j[s];
      }
      p.force[receivers[r]] += f;
      if constexpr (kTorque) p.torque[receivers[r]] += t;
    }
  });
  return touching;
}

// The pair loop's force, read-only: history copied (and not advanced), torques discarded.
template <class Normal, bool Tangential, RollingKind Rolling>
void pair_force_loop(const ContactLaw<Normal>& law, const Particles& p, const ContactList& contacts,
                     double period, double dt, std::vector<ContactForce>& out) {
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto hist = contacts.history();
  PairBatch batch;
  const auto flush = [&] {
    batch.evaluate<Normal, Tangential, Rolling>(law, dt, 0.0);
    for (std::size_t l = 0; l < batch.count; ++l) {
      out.push_back(ContactForce{batch.i[l], batch.j[l], batch.force.vec3(l)});
    }
    batch.count = 0;
  };
  out.clear();
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const Index j = col[k];
      const Vec3 d = separation(p, i, j, period);
      const double sum_r = p.radius[i] + p.radius[j];
      const double dist2 = d.squaredNorm();
      if (dist2 >= sum_r * sum_r || dist2 == 0.0) continue;
      batch.add(p, i, j, d, hist[k], k);
      if (batch.full()) flush();
    }
  }
  if (batch.count > 0) flush();
}

// The wall rolling springs of every particle (kWallRollingArrays), per wall part.
class WallRollingView {
 public:
  WallRollingView() = default;
  WallRollingView(Particles& p, std::size_t parts) {
    for (std::size_t w = 0; w < parts; ++w) {
      for (std::size_t c = 0; c < 3; ++c) {
        std::vector<double>* a = p.find_array(kWallRollingArrays[w][c]);
        if (a == nullptr) throw std::logic_error("wall rolling spring without its arrays");
        v_[w][c] = a->data();
      }
    }
  }
  Vec3 get(std::size_t part, Index i) const {
    return {v_[part][0][i], v_[part][1][i], v_[part][2][i]};
  }
  void set(std::size_t part, Index i, const Vec3& x) const {
    for (std::size_t c = 0; c < 3; ++c) v_[part][c][i] = x[static_cast<Eigen::Index>(c)];
  }

 private:
  std::array<std::array<double*, 3>, kWallParts> v_{};
};

// The wall contacts of the particles candidates[begin, end), by particle, then wall part.
// Returns how many there were (the contacts the kernel evaluated).
template <class Normal, bool Tangential, RollingKind Rolling>
std::size_t wall_rows(const ContactLaw<Normal>& law, Particles& p,
                      std::span<const Index> candidates, std::span<const std::uint8_t> near_parts,
                      std::size_t begin, std::size_t end, const Drum& drum, double omega,
                      WallHistory& history, double dt, double history_dt, WallBatch& batch) {
  const Vec3 wall_spin(0.0, 0.0, omega);
  const std::size_t parts = drum.periodic() ? 1 : kWallParts;
  constexpr bool kSpring = Rolling == RollingKind::spring;
  WallRollingView roll;
  if constexpr (kSpring) roll = WallRollingView(p, parts);
  const auto flush = [&] {
    batch.evaluate<Normal, Tangential, Rolling>(law, wall_spin, history_dt);
    for (std::size_t l = 0; l < batch.count; ++l) {
      const Index i = batch.i[l];
      history[i][batch.part[l]] = batch.xi.vec3(l);
      if constexpr (kSpring) roll.set(batch.part[l], i, batch.xi_r.vec3(l));
      p.force[i] += batch.force.vec3(l);
      if constexpr (Tangential || rolls(Rolling)) p.torque[i] += batch.torque_i.vec3(l);
    }
    batch.count = 0;
  };
  std::size_t contacts = 0;
  for (std::size_t q = begin; q < end; ++q) {
    const Index i = candidates[q];
    const Vec3& x = p.position[i];
    const double r = p.radius[i];
    const unsigned near = near_parts.empty() ? ~0u : near_parts[q];
    for (std::size_t part = 0; part < parts; ++part) {
      if (((near >> part) & 1u) == 0) continue;  // apart since the last build: history zero
      const WallContact c = drum.contact(static_cast<WallPart>(part), x, r);
      if (c.overlap <= 0.0) {
        history[i][part].setZero();
        if constexpr (kSpring) roll.set(part, i, Vec3::Zero());
        continue;
      }
      // The wall's spin enters through its surface velocity (branch length 0 on its side) and
      // through the relative rotation rate seen by rolling resistance.
      const Vec3 point = x - (r - 0.5 * c.overlap) * c.normal;
      batch.add(i, part, c.normal, c.overlap, r, p.mass[i], dt * p.inv_inertia[i],
                p.velocity[i] - Drum::wall_velocity(point, omega), p.omega[i], history[i][part]);
      if constexpr (kSpring) batch.set_rolling(roll.get(part, i));
      ++contacts;
      if (batch.full()) flush();
    }
  }
  if (batch.count > 0) flush();
  return contacts;
}

template <class Normal, bool Tangential, RollingKind Rolling>
std::size_t wall_loop(const ContactLaw<Normal>& law, Particles& p,
                      std::span<const Index> candidates, std::span<const std::uint8_t> near_parts,
                      const Drum& drum, double omega, WallHistory& history, double dt,
                      double history_dt, BlockDealer& dealer) {
  constexpr std::size_t kPerTask = 256;
  std::size_t contacts = 0;
  // Each candidate's forces and history are its own: who takes a task does not change the bits.
#pragma omp parallel reduction(+ : contacts)
  {
    WallBatch batch;
    deal_ranges(dealer, candidates.size(), kPerTask, [&](std::size_t begin, std::size_t end) {
      contacts += wall_rows<Normal, Tangential, Rolling>(
          law, p, candidates, near_parts, begin, end, drum, omega, history, dt, history_dt, batch);
    });
  }
  return contacts;
}

// The rolling spring of a linear viscoelastic normal law (RollingLaw::spring): k_r, gamma_r the
// scene's ratios of the law's k, gamma (the validation requires that normal law).
RollingSpring make_rolling_spring(const SceneConfig& s, const NormalVariant& normal,
                                  double rolling_friction) {
  const auto* law = std::get_if<LinearViscoelastic>(&normal);
  if (s.contact.rolling != RollingLaw::spring || law == nullptr) return {};
  return {s.contact.rolling_stiffness_ratio * law->stiffness,
          s.contact.rolling_damping_ratio * law->damping_coefficient, rolling_friction};
}

NormalVariant make_normal(const SceneConfig& s, const Material& other, double restitution) {
  if (s.contact.normal == NormalLaw::linear) {
    return LinearSpringDashpot(s.contact.linear_stiffness, restitution);
  }
  if (s.contact.normal == NormalLaw::linear_viscoelastic) {
    // m = 2 m* of two reference spheres = the mass of one (the peer's argument).
    const double r = s.contact.reference_radius;
    const double mass = s.material.density * (4.0 / 3.0) * std::numbers::pi * r * r * r;
    return LinearViscoelastic::from_collision(s.contact.collision_time, restitution, mass,
                                              s.contact.tangential_stiffness_ratio,
                                              s.contact.tangential_damping_ratio);
  }
  return HertzNormal(effective_youngs_modulus(s.material, other),
                     effective_shear_modulus(s.material, other), restitution);
}

}  // namespace

ContactModel::ContactModel(const SceneConfig& scene) {
  validate_laws(scene);
  pair_ = {make_normal(scene, scene.material, scene.material.restitution),
           MindlinTangential{scene.material.friction},
           RollingResistance{scene.material.rolling_friction},
           {}};
  pair_.rolling_spring = make_rolling_spring(scene, pair_.normal, scene.material.rolling_friction);
  wall_ = {make_normal(scene, scene.wall, scene.wall.restitution),
           MindlinTangential{scene.wall.friction},
           RollingResistance{scene.wall.rolling_friction},
           {}};
  wall_.rolling_spring = make_rolling_spring(scene, wall_.normal, scene.wall.rolling_friction);
  spring_ = scene.contact.rolling == RollingLaw::spring;
  pair_tangential_ = scene.material.friction > 0.0;
  pair_rolling_ = scene.material.rolling_friction > 0.0;
  wall_tangential_ = scene.wall.friction > 0.0;
  wall_rolling_ = scene.wall.rolling_friction > 0.0;
  cohesive_ = CohesiveParts(scene);
  pair_range_ = cohesive_.range();
  pair_block_rows_ = static_cast<std::size_t>(scene.performance.pair_block_rows);
  const auto add_mesh_law = [&](const MeshMaterial& m) {
    const Material material{scene.wall.density, m.youngs_modulus, m.poisson_ratio,
                            m.restitution,      m.friction,       m.rolling_friction};
    MeshLaw law;
    law.law = {make_normal(scene, material, m.restitution),
               MindlinTangential{m.friction},
               RollingResistance{m.rolling_friction},
               {}};
    law.law.rolling_spring = make_rolling_spring(scene, law.law.normal, m.rolling_friction);
    law.tangential = m.friction > 0.0;
    law.rolling = m.rolling_friction > 0.0;
    mesh_torque_ = mesh_torque_ || law.tangential || law.rolling;
    mesh_laws_.push_back(law);
  };
  for (const MeshWallConfig& c : scene.meshes) add_mesh_law(c.material);
  for (const LifterWallConfig& c : scene.lifters) add_mesh_law(c.material);
}

double ContactModel::mesh_elastic_energy(std::size_t wall, double delta, double r) const {
  return std::visit([&](const auto& n) { return n.elastic_energy(delta, r); },
                    mesh_laws_[wall].law.normal);
}

std::vector<std::string_view> ContactModel::particle_arrays(std::size_t wall_parts) const {
  std::vector<std::string_view> names = cohesive_.particle_arrays(wall_parts);
  if (wall_rolling_spring()) {
    for (std::size_t w = 0; w < wall_parts; ++w) {
      names.insert(names.end(), kWallRollingArrays[w].begin(), kWallRollingArrays[w].end());
    }
  }
  if (!mesh_laws_.empty()) {
    const bool rolling = spring_ && std::any_of(mesh_laws_.begin(), mesh_laws_.end(),
                                                [](const MeshLaw& l) { return l.rolling; });
    for (std::size_t k = 0; k < kMeshSlots; ++k) {
      names.push_back(kMeshPatchArrays[k]);
      names.insert(names.end(), kMeshSpringArrays[k].begin(), kMeshSpringArrays[k].end());
      if (rolling) {
        names.insert(names.end(), kMeshRollingArrays[k].begin(), kMeshRollingArrays[k].end());
      }
    }
  }
  return names;
}

double ContactModel::pair_range(std::uint8_t, std::uint8_t) const {
  // One liquid for every class pair for now; a per-class law would look its pair up here.
  return pair_range_;
}

std::size_t ContactModel::add_pair_forces(Particles& p, ContactList& contacts,
                                          PairForceBuffers& buffers, double period, double dt,
                                          double history_dt) const {
  const std::size_t touching =
      add_pair_forces_parallel(p, contacts, buffers, period, dt, history_dt, false);
  add_pair_forces_ordered(p, contacts, buffers, period, history_dt, nullptr);
  return touching;
}

std::size_t ContactModel::add_pair_forces_parallel(Particles& p, ContactList& contacts,
                                                   PairForceBuffers& buffers, double period,
                                                   double dt, double history_dt,
                                                   bool list_events) const {
  std::size_t touching = 0;
  const bool cohesive = cohesive_.any();
  const TouchingPull pull =
      cohesive ? touching_pull(cohesive_, contacts, history_dt) : TouchingPull{};
  with_law(pair_, pair_tangential_, rolling_kind(pair_rolling_, spring_),
           [&]<class N, bool Tangential, RollingKind Rolling>(const ContactLaw<N>& law) {
             touching = cohesive
                            ? pair_loop<N, Tangential, Rolling, true>(law, p, contacts, buffers,
                                                                      pair_block_rows_, period, dt,
                                                                      history_dt, pull)
                            : pair_loop<N, Tangential, Rolling, false>(law, p, contacts, buffers,
                                                                       pair_block_rows_, period, dt,
                                                                       history_dt, pull);
           });
  if (cohesive) {
    cohesion_pass_one(cohesive_, p, contacts, period, history_dt, buffers.cohesion, list_events);
  }
  return touching;
}

void ContactModel::add_pair_forces_ordered(Particles& p, ContactList& contacts,
                                           const PairForceBuffers& buffers, double period,
                                           double history_dt,
                                           const BridgeEventFilms* replay) const {
  if (!cohesive_.any()) return;
  cohesion_ordered_pass(cohesive_, p, contacts, period, history_dt, buffers.cohesion, replay);
}

std::size_t ContactModel::add_wall_forces(Particles& p, std::span<const Index> candidates,
                                          const Drum& drum, double omega, WallHistory& history,
                                          double dt, double history_dt,
                                          std::span<const std::uint8_t> near_parts) const {
  if (!near_parts.empty() && near_parts.size() != candidates.size()) {
    throw std::logic_error("add_wall_forces: near_parts does not match the candidates");
  }
  std::size_t contacts = 0;
  with_law(wall_, wall_tangential_, rolling_kind(wall_rolling_, spring_),
           [&]<class N, bool Tangential, RollingKind Rolling>(const ContactLaw<N>& law) {
             contacts =
                 wall_loop<N, Tangential, Rolling>(law, p, candidates, near_parts, drum, omega,
                                                   history, dt, history_dt, wall_blocks_);
           });
  if (cohesive_.any()) {
    cohesion_wall_loop(cohesive_, p, candidates, near_parts, drum, omega, history_dt);
  }
  return contacts;
}

void ContactModel::pair_forces(const Particles& p, const ContactList& contacts, double period,
                               double dt, std::vector<ContactForce>& out) const {
  std::visit(
      [&](const auto& normal) {
        const auto law = make_law(normal, pair_.tangential, pair_.rolling, pair_.rolling_spring);
        using N = std::decay_t<decltype(normal)>;
        if (pair_tangential_) {
          pair_force_loop<N, true, RollingKind::none>(law, p, contacts, period, dt, out);
        } else {
          pair_force_loop<N, false, RollingKind::none>(law, p, contacts, period, dt, out);
        }
      },
      pair_.normal);
}
// The cohesive forces (bridges, adhesion) merged into the contact forces by (i, j).
void ContactModel::add_cohesive_forces(const Particles& p, const ContactList& contacts,
                                       double period, std::vector<ContactForce>& out) const {
  if (!cohesive_.any()) return;
  std::vector<Bond> bonds;
  cohesion_bonds(cohesive_, p, contacts, period, bonds);
  if (bonds.empty()) return;
  std::vector<ContactForce> merged;
  merged.reserve(out.size() + bonds.size());
  std::size_t a = 0;
  for (const Bond& b : bonds) {
    for (; a < out.size() && std::pair(out[a].i, out[a].j) < std::pair(b.i, b.j); ++a) {
      merged.push_back(out[a]);
    }
    const Vec3 d = separation(p, b.i, b.j, period);
    const Vec3 pull = (-b.force / d.norm()) * d;  // on i, towards j
    if (a < out.size() && out[a].i == b.i && out[a].j == b.j) {
      merged.push_back({b.i, b.j, out[a].force + pull});
      ++a;
    } else {
      merged.push_back({b.i, b.j, pull});
    }
  }
  merged.insert(merged.end(), out.begin() + static_cast<std::ptrdiff_t>(a), out.end());
  out.swap(merged);
}

void ContactModel::bonds(const Particles& p, const ContactList& contacts, double period,
                         std::vector<Bond>& out) const {
  cohesion_bonds(cohesive_, p, contacts, period, out);
}

double ContactModel::pair_elastic_energy(double delta, double r_eff) const {
  return std::visit([&](const auto& n) { return n.elastic_energy(delta, r_eff); }, pair_.normal);
}

double ContactModel::wall_elastic_energy(double delta, double r) const {
  return std::visit([&](const auto& n) { return n.elastic_energy(delta, r); }, wall_.normal);
}

}  // namespace drumlab
