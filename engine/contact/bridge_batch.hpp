#pragma once
// Batches of listed pairs for pass 1 of the liquid bridge (engine/contact/cohesion_loops.cpp), as
// PairBatch is for the contact force (contact_kernel.hpp): a bridged pair's force is a chain of
// square roots and divisions (distance, Willett's radius, s~, the force, the direction), one pair
// at a time each waits for the last, and whether the pair touches (F = F0) or is apart decides a
// branch no predictor learns. The batch gathers up to kSize pairs into arrays of each input and
// evaluates them in a loop without branches that the compiler turns into SIMD code, with the same
// operations in the same order as LiquidBridge::force, so the results are the same bits.
//
// What the batch decides for each pair (the scene's bridge alone: no viscous term, no sjkr):
//   event:  the bridge may rupture (its gap is within 1e-6 of s_rup or beyond, as
//           BridgeLiquid::ruptured's first two tests say; the caller settles these few with
//           ruptured() itself, from `gaps`) or a pair without one touches (it forms): the films
//           change, pass 2 does it in the serial order;
//   live:   the bridge holds: its force, attractive along the line of centres;
//   else:   nothing acts.
// It is the liquid bridge's batch for the cohesive loops (PartBatch<LiquidBridge>): a scene whose
// only cohesive part is the plain bridge (applies(): no viscous term) runs pass 1 through it.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "engine/contact/contact_kernel.hpp"
#include "engine/contact/liquid_bridge.hpp"
#include "engine/types.hpp"

namespace drumlab {

struct BridgeBatch {
  static constexpr std::size_t kSize = 64;
  /// What evaluate() found for a lane (doubles, so the loop needs no second vector width).
  static constexpr double kNothing = 0.0;
  static constexpr double kLive = 1.0;
  static constexpr double kEvent = 2.0;

  std::size_t count = 0;
  std::uint32_t k[kSize];  ///< the pair's place in the contact list
  Index i[kSize];
  Index j[kSize];
  Lanes3<kSize> d;  ///< separation x_i - x_j
  alignas(64) double r_i[kSize];
  alignas(64) double r_j[kSize];
  alignas(64) double volume[kSize];  ///< the bridge's volume (0: none)
  Lanes3<kSize> force;               ///< after evaluate: the force on j of a live bridge
  alignas(64) double gaps[kSize];    ///< after evaluate: the surface gap
  alignas(64) double kind[kSize];
  alignas(64) double xx[kSize];  ///< scratch of evaluate
  alignas(64) double yy[kSize];

  bool full() const { return count == kSize; }
  /// The contact pair loop adds the pull of overlapping pairs' live bridges (TouchingPull,
  /// add_touching_pull below); pass 1 leaves them out.
  static constexpr bool kTouchingInPairLoop = true;
  /// Whether a scene's bridge can run its pass 1 in batches (no viscous term).
  static bool applies(const LiquidBridge& b) { return b.viscosity == 0.0; }

  /// Adds pair (i, j), contact `contact`, at separation dij, radii ri, rj, bridge volume v.
  [[gnu::always_inline]] void add(Index pi, Index pj, std::uint32_t contact, const Vec3& dij,
                                  double ri, double rj, double v) {
    const std::size_t l = count;
    k[l] = contact;
    i[l] = pi;
    j[l] = pj;
    d.set(l, dij);
    r_i[l] = ri;
    r_j[l] = rj;
    volume[l] = v;
    ++count;
  }

  /// add() with the pair's state in the contact list (the bridge's scalars).
  [[gnu::always_inline]] void add(Index pi, Index pj, std::uint32_t contact, const Vec3& dij,
                                  double ri, double rj, const double* state) {
    add(pi, pj, contact, dij, ri, rj, state[0]);
  }
  void evaluate(const LiquidBridge& b) { evaluate(b.pair); }
  /// After evaluate: whether anything acts on lane l.
  bool acts(std::size_t l) const { return kind[l] != kNothing; }
  /// After evaluate, for a lane that acts: true if its bridge forms or ruptures (its films change:
  /// the ordered pass does it; a lane near s_rup settled by ruptured() itself); else its bridge
  /// ages by dt in `state` and force holds its pull.
  bool settle(std::size_t l, const LiquidBridge& b, double* state, double dt) const {
    bool event = kind[l] == kEvent;
    if (event && volume[l] > 0.0) event = b.pair.ruptured(gaps[l], volume[l]);  // within 1e-6
    if (!event) state[1] += dt;                                                 // the bridge ages
    return event;
  }

  /// Sets kind and, for live bridges, force of every lane. Not inlined: GCC 12 vectorizes the
  /// loop through `this`, not over a batch that is a local of the caller ("no vectype").
  [[gnu::noinline]] void evaluate(const BridgeLiquid& liquid) {
    const std::size_t n = pad_lanes(*this);
    const double shrink = 1.0 / (1.0 + 0.5 * liquid.contact_angle);
    constexpr double kBelow = 1.0 - 1e-6;  // BridgeLiquid::ruptured: surely intact below this
    // |d|^2 as Eigen's Vec3::squaredNorm rounds it (the scalar path's distance):
    // fma(z, z, x^2 + y^2) with both squares rounded; a loop of its own, so that the compiler
    // cannot fuse x^2 + y^2 into one multiply-add.
    for (std::size_t l = 0; l < n; ++l) {
      xx[l] = d.x[l] * d.x[l];
      yy[l] = d.y[l] * d.y[l];
    }
    for (std::size_t l = 0; l < n; ++l) {
      const LaneVec dl = d.get(l);
      const double dist = std::sqrt(std::fma(dl.z, dl.z, xx[l] + yy[l]));
      const double gap = dist - (r_i[l] + r_j[l]);
      const double v = volume[l];
      const bool live = v > 0.0;
      const double g = gap * shrink;
      const bool may_rupture = (gap > 0.0) & !(g * g * g < kBelow * v);
      const bool event = (live & may_rupture) | (!live & !(gap > 0.0));
      // LiquidBridge::force with the touching branch folded in: at s~ = 0 the denominator is
      // exactly 1 and F = F0.
      const double r_eff = LiquidBridge::pair_radius(r_i[l], r_j[l]);
      const double s = std::max(gap, 0.0) * std::sqrt(r_eff / (live ? v : 1.0));
      const double pull = liquid.touching_force(r_eff) / (1.0 + (1.05 + 2.5 * s) * s);
      force.set(l, (pull / dist) * dl);
      gaps[l] = gap;
      const double held = live ? kLive : kNothing;
      kind[l] = event ? kEvent : held;
    }
  }

 private:
  friend std::size_t pad_lanes<BridgeBatch>(BridgeBatch&);
  void copy_lane(std::size_t from, std::size_t to) {
    d.set(to, d.get(from));
    r_i[to] = r_i[from];
    r_j[to] = r_j[from];
    volume[to] = volume[from];
  }
};

template <>
struct PartBatch<LiquidBridge> {
  using type = BridgeBatch;
};

/// After PairBatch::evaluate in the contact pair loop (contact_model.cpp), for a scene whose
/// bridges pass 1 runs in BridgeBatch: every lane (an overlapping pair) whose bridge lives gets
/// its pull added to its force on i, F0 = 2 pi R gamma cos(theta) towards j (touching: s~ = 0, so
/// LiquidBridge::force is F0 and no event can happen), computed as BridgeBatch::evaluate computes
/// it; and its bridge ages by dt. The force on j (minus it) and the sums follow the contact's.
inline void add_touching_pull(const TouchingPull& t, PairBatch& b) {
  alignas(64) double volume[PairBatch::kSize];
  alignas(64) double xx[PairBatch::kSize];
  alignas(64) double yy[PairBatch::kSize];
  const std::size_t n = b.count;
  for (std::size_t l = 0; l < n; ++l) {
    double* s = t.state + b.k[l] * t.stride;
    volume[l] = s[0];
    s[1] += s[0] > 0.0 ? t.dt : 0.0;  // a live bridge ages (+0 leaves any other age as it is)
  }
  for (std::size_t l = 0; l < n; ++l) {  // the squares rounded as in BridgeBatch::evaluate
    xx[l] = b.d.x[l] * b.d.x[l];
    yy[l] = b.d.y[l] * b.d.y[l];
  }
  for (std::size_t l = 0; l < n; ++l) {
    const LaneVec d = b.d.get(l);
    const double dist = std::sqrt(std::fma(d.z, d.z, xx[l] + yy[l]));
    const double pull = t.f0_per_radius * LiquidBridge::pair_radius(b.r_i[l], b.r_j[l]);
    const LaneVec f = (pull / dist) * d;  // on j, towards i
    const bool live = volume[l] > 0.0;
    b.force.x[l] = live ? b.force.x[l] - f.x : b.force.x[l];
    b.force.y[l] = live ? b.force.y[l] - f.y : b.force.y[l];
    b.force.z[l] = live ? b.force.z[l] - f.z : b.force.z[l];
  }
}

}  // namespace drumlab
