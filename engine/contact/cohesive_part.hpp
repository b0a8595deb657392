#pragma once
// The interface of a cohesive law part: a law that acts beside the contact force, possibly beyond
// contact (a liquid bridge, dry adhesion). The contact parts (normal, tangential, rolling) are
// composed by ContactModel's with_law into one templated pair loop; the cohesive parts are composed
// here, into the loops of cohesion_loops.cpp, which are generic over them. The pattern is LAMMPS's
// granular sub-models (src/GRANULAR/gran_sub_mod.h: `beyond_contact`, `size_history`,
// `pulloff_distance()`), as value types checked at compile time instead of virtual classes, so
// that a part inlines into the pass over the listed pairs.
//
// A part P (see CohesiveLaw below; liquid_bridge.hpp and sjkr_cohesion.hpp are the two parts) says:
//   range      range() / wall_range(): the largest surface gap (m) at which it acts on a pair / on
//   a
//              particle and the wall (0: only in contact). The search margin and the wall
//              candidates' reach follow from the largest over the parts.
//   state      kStateSize scalars per listed pair (ContactList::state(), at the part's offset; a
//              new pair's are zero) and, for the wall, its per-particle arrays
//              (particle_arrays(): registered by Simulation, carried by re-ordering, migration and
//              checkpoints) with wall_state(), the view of them one wall pass uses.
//              live(s): the state says the part acts even apart (a bridge holds; an adhesive
//              contact was made). The pass over the listed pairs skips, without branches, every
//              pair that neither touches nor has a live part (cohesion_loops.cpp).
//   force      advance_pair(): advances a pair's state by dt and adds its attraction (N, > 0
//              pulls the two together) to `pull`; advance_wall() the same with the wall.
//   events     event(s, gap): the state changes at this step in a way that moves liquid between
//              the particles' films (a bridge forms or ruptures). Such a pair is done in the
//              ordered pass, one thread, in the serial (i, j) order (and replayed across MPI
//              ranks, parallel/bridge_events.hpp); every other pair in parallel. drop(): a pair
//              the contact list dropped while the part's state was live (its liquid goes back).
//              kHasEvents: whether the part has events at all (false: event() is never asked);
//              moves_films(): whether its events move liquid between films (migration: the
//              film array is then kept and, across MPI ranks, the events replayed).
//   bonds      bonds(): whether the part can link two particles for agglomerate analysis;
//              bonded(s), bond_share(): the link's liquid, force and age (contact/bond.hpp).
//   liquid     kHoldsLiquid, liquid(s): the liquid a pair's state holds (m^3, in
//              LiquidTotals::bridges); films and wall bridges are per-particle arrays.
//   scene      from_scene(): the part of a scene (nullopt: the scene does not have it); its
//              parameters are checked before, by validate_laws (scene/scene_validation.hpp).
//   batch      optional, for speed: PartBatch<P>::type, a batch that evaluates pass 1 of a scene
//              whose only cohesive part is P in SIMD lanes with the same bits (bridge_batch.hpp:
//              add(), evaluate(), acts(), settle(), the lanes' i, j, k, force; applies(law);
//              kTouchingInPairLoop: the contact pair loop adds the pull of overlapping pairs
//              with live state, and pass 1 leaves them out: TouchingPull, cohesion_loops.hpp).
// A part is registered once, in CohesiveParts (cohesive_laws.hpp); the order there is the order
// in which the parts' forces add up in a pair (it fixes the bits).
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/drum.hpp"
#include "engine/particles.hpp"
#include "engine/scene/scene_config.hpp"
#include "engine/types.hpp"

namespace drumlab {

/// A listed pair (i, j) at the current positions, as a part's advance_pair / bond_share sees it.
struct PairGap {
  const Particles& p;
  Index i;
  Index j;
  const Vec3& d;  ///< x_i - x_j (nearest image)
  double dist;    ///< |d| > 0
  double gap;     ///< dist - (r_i + r_j), m; negative while they overlap
};

/// Gap (m, negative: overlap) and unit normal (from the wall into the particle) of a sphere
/// against one wall part, also when apart (Drum::contact reports only overlaps).
struct WallGap {
  double gap = 0.0;
  Vec3 normal = Vec3::Zero();
};
/// (Inlined: the wall pass calls it for every wall candidate and part.)
[[gnu::always_inline]] inline WallGap wall_gap(const Drum& drum, WallPart part, const Vec3& x,
                                               double r) {
  if (part == WallPart::cap_low) return {x.z() - r, Vec3(0.0, 0.0, 1.0)};
  if (part == WallPart::cap_high) return {drum.depth() - x.z() - r, Vec3(0.0, 0.0, -1.0)};
  const double rho = std::sqrt(x.x() * x.x() + x.y() * x.y());
  if (rho == 0.0) return {drum.radius() - r, Vec3::Zero()};
  return {drum.radius() - rho - r, Vec3(-x.x() / rho, -x.y() / rho, 0.0)};
}

/// Particle i against wall part `part` of the drum turning at omega (rad/s), for advance_wall.
struct WallSite {
  const Particles& p;
  Index i;
  std::size_t part;
  const WallGap& g;
  double omega;
};

/// What one part contributes to a Bond (contact/bond.hpp).
struct BondShare {
  double volume = 0.0;  ///< liquid held, m^3
  double force = 0.0;   ///< attraction at the current state, N
  double age = 0.0;     ///< time since the link formed, s
};

/// A part's SIMD batch for pass 1 (the `batch` line above); void: pair by pair.
template <class P>
struct PartBatch {
  using type = void;
};

template <class P>
concept CohesiveLaw = requires(const P& law, const SceneConfig& scene, const double* cs, double* s,
                               double* film, const PairGap& pg, const WallSite& ws,
                               typename P::WallState& wall, Particles& p, double& pull) {
  { P::kStateSize } -> std::convertible_to<std::size_t>;
  { P::kHasEvents } -> std::convertible_to<bool>;
  { P::kHoldsLiquid } -> std::convertible_to<bool>;
  { P::from_scene(scene) } -> std::same_as<std::optional<P>>;
  { law.range() } -> std::same_as<double>;
  { law.wall_range() } -> std::same_as<double>;
  { law.particle_arrays(std::size_t{}) } -> std::same_as<std::vector<std::string_view>>;
  { law.moves_films() } -> std::same_as<bool>;
  { P::live(cs) } -> std::same_as<bool>;
  { law.event(cs, 0.0) } -> std::same_as<bool>;
  law.advance_pair(pg, s, film, 0.0, pull);
  law.drop(s, film, Index{}, Index{});
  { law.acts_at_wall() } -> std::same_as<bool>;
  { law.wall_state(p, std::size_t{}) } -> std::same_as<typename P::WallState>;
  { law.wall_live(wall, Index{}, std::size_t{}) } -> std::same_as<bool>;
  law.advance_wall(wall, ws, film, 0.0, pull);
  { law.bonds() } -> std::same_as<bool>;
  { P::bonded(cs) } -> std::same_as<bool>;
  { law.bond_share(pg, cs) } -> std::same_as<BondShare>;
  { P::liquid(cs) } -> std::same_as<double>;
};

/// The cohesive parts of one scene: each registered law, present or not, and the offset of its
/// scalars in a contact's state. The loops visit the present parts in the order of Laws.
template <CohesiveLaw... Laws>
class CohesivePartsOf {
 public:
  static constexpr std::size_t kCount = sizeof...(Laws);

  CohesivePartsOf() = default;
  /// Each law's part of a validated `scene` (Law::from_scene), state laid out in order.
  explicit CohesivePartsOf(const SceneConfig& scene) {
    std::size_t size = 0;
    for_each_law([&]<std::size_t K, class Law>() {
      auto& part = std::get<K>(laws_);
      part = Law::from_scene(scene);
      offset_[K] = part ? size : 0;  // an absent part's offset stays inside the state
      if (part) size += Law::kStateSize;
    });
    state_size_ = size;
  }

  bool any() const {
    return std::apply([](const auto&... part) { return (part.has_value() || ...); }, laws_);
  }
  /// Scalars per contact over all present parts (ContactList::set_state_size).
  std::size_t state_size() const { return state_size_; }
  /// The largest pair / wall range of the present parts (m; 0 with none).
  double range() const {
    double r = 0.0;
    for_each([&](const auto& law, std::size_t) { r = std::max(r, law.range()); });
    return r;
  }
  double wall_range() const {
    double r = 0.0;
    for_each([&](const auto& law, std::size_t) { r = std::max(r, law.wall_range()); });
    return r;
  }
  /// The per-particle arrays the present parts keep (films, wall bridges), each once.
  std::vector<std::string_view> particle_arrays(std::size_t wall_parts) const {
    std::vector<std::string_view> names;
    for_each([&](const auto& law, std::size_t) {
      for (const std::string_view n : law.particle_arrays(wall_parts)) {
        if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
      }
    });
    return names;
  }

  /// Law's part, or nullptr if the scene does not have it.
  template <class Law>
  const Law* get() const {
    const auto& part = std::get<std::optional<Law>>(laws_);
    return part ? &*part : nullptr;
  }
  /// Where Law's scalars start in a contact's state.
  template <class Law>
  std::size_t offset() const {
    return offset_[index_of<Law>()];
  }

  /// f(law, offset) for every present part, in the order of Laws.
  template <class F>
  void for_each(F&& f) const {
    for_each_law([&]<std::size_t K, class Law>() {
      if (const auto& part = std::get<K>(laws_)) f(*part, offset_[K]);
    });
  }
  /// f.template operator()<K, Law>() for every registered law (present or not).
  template <class F>
  static void for_each_law(F&& f) {
    [&]<std::size_t... K>(std::index_sequence<K...>) {
      (f.template operator()<K, Laws>(), ...);
    }
    (std::index_sequence_for<Laws...>{});
  }
  /// The part K if present, else nullptr.
  template <std::size_t K>
  const auto* at() const {
    const auto& part = std::get<K>(laws_);
    return part ? &*part : nullptr;
  }
  std::size_t offset_at(std::size_t k) const { return offset_[k]; }

 private:
  template <class Law>
  static constexpr std::size_t index_of() {
    constexpr std::array<bool, kCount> same = {std::is_same_v<Law, Laws>...};
    for (std::size_t k = 0; k < kCount; ++k) {
      if (same[k]) return k;
    }
    return kCount;
  }

  std::tuple<std::optional<Laws>...> laws_;
  std::array<std::size_t, kCount> offset_{};
  std::size_t state_size_ = 0;
};

}  // namespace drumlab
