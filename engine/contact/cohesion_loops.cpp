#include "engine/contact/cohesion_loops.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include "engine/contact/bridge_batch.hpp"
#include "engine/contact/touch_sift.hpp"
#include "engine/periodic.hpp"

namespace drumlab {
namespace {

constexpr std::size_t kParts = CohesiveParts::kCount;
template <std::size_t K>
using LawOf = std::remove_cvref_t<decltype(*std::declval<const CohesiveParts&>().at<K>())>;

// f(law, offset) for every present part with events (kHasEvents).
template <class F>
void for_each_with_events(const CohesiveParts& parts, F&& f) {
  parts.for_each([&](const auto& law, std::size_t off) {
    if constexpr (std::remove_cvref_t<decltype(law)>::kHasEvents) f(law, off);
  });
}

// The film array if a present part's events move liquid between films (migration), else nullptr.
double* film_of(const CohesiveParts& parts, Particles& p) {
  bool moves = false;
  parts.for_each([&](const auto& law, std::size_t) { moves = moves || law.moves_films(); });
  if (!moves) return nullptr;
  std::vector<double>* film = p.find_array(kLiquidFilmArray);
  if (film == nullptr) throw std::logic_error("liquid migration without a film array");
  return film->data();
}

// Whether some present part's state at `st` is live (Law::live), without branches: each
// registered part's presence flag and offset are read once, before the loop.
struct LiveTest {
  std::array<bool, kParts> present{};
  std::array<std::size_t, kParts> offset{};  // < state size (an absent part's is 0)
  explicit LiveTest(const CohesiveParts& parts) {
    CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
      present[K] = parts.at<K>() != nullptr;
      offset[K] = parts.offset_at(K);
    });
  }
  [[gnu::always_inline]] bool operator()(const double* st) const {
    bool live = false;
    CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
      live = live | (present[K] & Law::live(st + offset[K]));
    });
    return live;
  }
};

// One listed pair: advances every part's state, returns the sum of their attractions (N, > 0
// pulls i towards j), added in the parts' order. film: nullptr in pass 1 (no event there).
double pair_attraction(const CohesiveParts& parts, const PairGap& g, double* state, double* film,
                       double dt) {
  double pull = 0.0;
  parts.for_each(
      [&](const auto& law, std::size_t off) { law.advance_pair(g, state + off, film, dt, pull); });
  return pull;
}

// True if some part has an event on the pair at this step (its films change).
bool any_event(const CohesiveParts& parts, const double* state, double gap) {
  bool event = false;
  for_each_with_events(parts, [&](const auto& law, std::size_t off) {
    event = event || law.event(state + off, gap);
  });
  return event;
}

// Whether a dropped pair's state holds something a part with events must settle, and the liquid
// its events' part holds (the volume an MPI replay sees rupture).
bool live_for_events(const CohesiveParts& parts, const double* state) {
  bool live = false;
  for_each_with_events(
      parts, [&](const auto& law, std::size_t off) { live = live || law.live(state + off); });
  return live;
}
double event_liquid(const CohesiveParts& parts, const double* state) {
  double v = 0.0;
  for_each_with_events(parts, [&](const auto& law, std::size_t off) {
    if constexpr (std::remove_cvref_t<decltype(law)>::kHoldsLiquid) v = law.liquid(state + off);
  });
  return v;
}

// The force of listed pair k (i, j) without an event (its state advanced), or a marked entry if
// it has one; nothing if no part acts on it.
[[gnu::always_inline]] inline void cohesion_entry(const CohesiveParts& parts, const Particles& p,
                                                  double* st, Index i, Index j, std::size_t k,
                                                  const Vec3& d, double dt,
                                                  CohesionBuffers::Entry* out, std::size_t& n) {
  const double dist = d.norm();
  const double gap = dist - (p.radius[i] + p.radius[j]);
  const auto kk = static_cast<std::uint32_t>(k);
  if (any_event(parts, st, gap)) {
    out[n++] = {i, j, kk, 1, Vec3::Zero()};
    return;
  }
  const double pull = pair_attraction(parts, {p, i, j, d, dist, gap}, st, nullptr, dt);
  if (pull != 0.0) out[n++] = {i, j, kk, 0, (pull / dist) * d};
}

// Visits, by increasing k, the listed pairs of the rows of cohesion block `block` on which a
// cohesive part may act (take_mask of touch_sift.hpp: distinct centres, and touching or live). Most
// listed pairs are apart, with no live part state: nothing acts (a bridge forms only on contact;
// sjkr acts only while overlapping). The block's entries are contiguous in k, so they are sifted in
// chunks of kSiftChunk across row ends as bit masks (touch_sift.hpp) of the touch marks the contact
// pair loop left (no partner is gathered for it) and of live_mask(k0, n), bit q: entry k0 + q live;
// visit(i, k) then runs on the pairs that remain, each pair's row i read from entry_rows() (the
// pair loop indexed it this step). Sifting row by row paid each short row's loop exits, ~8 entries
// a row; a cursor over the row starts, a mispredicted exit for most pairs; a scalar sift, a dozen
// instructions an entry. kPulled: the pair loop has done the overlapping pairs with live state
// (take_not_pulled_mask).
template <bool kPulled = false, class LiveMask, class Visit>
[[gnu::always_inline]] inline void for_each_acting_pair(const ContactList& contacts,
                                                        const std::uint8_t* mark, std::size_t block,
                                                        LiveMask&& live_mask, Visit&& visit) {
  const auto row = contacts.row_start();
  const auto row_of = contacts.entry_rows();
  const std::size_t begin = block * kCohesionBlockRows;
  const std::size_t end = std::min(contacts.rows(), begin + kCohesionBlockRows);
  for (std::size_t k0 = row[begin]; k0 < row[end]; k0 += kSiftChunk) {
    const std::size_t n = std::min(row[end] - k0, kSiftChunk);
    const MarkMasks marks = mark_masks(mark + k0, n);
    const std::uint64_t live = live_mask(k0, n);
    const std::uint64_t taken =
        kPulled ? take_not_pulled_mask(marks, live) : take_mask(marks, live);
    for_each_bit(taken, [&](std::size_t q) { visit(row_of[k0 + q], k0 + q); });
  }
}

// live_mask of for_each_acting_pair by a test of each entry's state: bit q is live(k0 + q).
template <class Live>
[[gnu::always_inline]] inline auto live_mask_of(Live&& live) {
  return [live](std::size_t k0, std::size_t n) {
    std::uint64_t m = 0;
    for (std::size_t q = 0; q < n; ++q) m |= static_cast<std::uint64_t>(live(k0 + q)) << q;
    return m;
  };
}

// Pass 1 (cohesion_pass_one) over the rows of block `block`, any composition of parts: every
// pair that may act (for_each_acting_pair) evaluated one at a time.
[[gnu::noinline]] void cohesion_block(const CohesiveParts& parts, const LiveTest& live,
                                      const Particles& p, ContactList& contacts, double period,
                                      double dt, std::size_t block, CohesionBuffers& buffers) {
  const auto col = contacts.col();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  CohesionBuffers::Entry* out =
      buffers.entries.data() + contacts.row_start()[block * kCohesionBlockRows];
  std::size_t n = 0;
  for_each_acting_pair(contacts, buffers.mark.data(), block,
                       live_mask_of([&](std::size_t k) { return live(&state[k * stride]); }),
                       [&](std::size_t i, std::size_t k) {
                         const Index j = col[k];
                         cohesion_entry(parts, p, &state[k * stride], static_cast<Index>(i), j, k,
                                        nearest_image(p.position[i], p.position[j], period), dt,
                                        out, n);
                       });
  buffers.count[block] = n;
}

// Pass 1 over block `block` for a scene whose only cohesive part is `law`, with the SIMD batch
// PartBatch<Law> (bridge_batch.hpp): the same entries as cohesion_block, in the same order; the
// pairs that may act are evaluated in the batch's lanes. A batch with kTouchingInPairLoop leaves
// out the pairs the pair loop has pulled (touching_pull).
template <class Law>
[[gnu::noinline]] void batched_block(const Law& law, std::size_t off, const Particles& p,
                                     ContactList& contacts, double period, double dt,
                                     std::size_t block, CohesionBuffers& buffers) {
  const auto col = contacts.col();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  CohesionBuffers::Entry* out =
      buffers.entries.data() + contacts.row_start()[block * kCohesionBlockRows];
  std::size_t n = 0;
  using Batch = typename PartBatch<Law>::type;
  Batch batch;
  const auto flush = [&] {
    batch.evaluate(law);
    for (std::size_t l = 0; l < batch.count; ++l) {
      if (!batch.acts(l)) continue;
      const bool event = batch.settle(l, law, &state[batch.k[l] * stride + off], dt);
      out[n++] = {batch.i[l], batch.j[l], batch.k[l], event ? 1u : 0u,
                  event ? Vec3::Zero() : batch.force.vec3(l)};
    }
    batch.count = 0;
  };
  // A plain liquid bridge alone (state size 2, live while its volume s[0] > 0): its live flags
  // by SIMD compares.
  constexpr bool kBridge = std::is_same_v<Law, LiquidBridge>;
  const bool bridge_only = kBridge && stride == 2 && off == 0;
  const auto by_entry =
      live_mask_of([&](std::size_t k) { return Law::live(&state[k * stride + off]); });
  for_each_acting_pair<Batch::kTouchingInPairLoop>(
      contacts, buffers.mark.data(), block,
      [&](std::size_t k0, std::size_t n) {
        return bridge_only ? positive_even_mask(&state[k0 * 2], n) : by_entry(k0, n);
      },
      [&](std::size_t i, std::size_t k) {
        const Index j = col[k];
        batch.add(static_cast<Index>(i), j, static_cast<std::uint32_t>(k),
                  nearest_image(p.position[i], p.position[j], period), p.radius[i], p.radius[j],
                  &state[k * stride + off]);
        if (batch.full()) flush();
      });
  flush();
  buffers.count[block] = n;
}

// The registered part that runs pass 1 in batches: the scene's only present part, if it has a
// PartBatch that applies to it; kParts: none (pair by pair).
std::size_t batched_part(const CohesiveParts& parts) {
  std::size_t present = 0, batched = kParts;
  CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
    const Law* law = parts.at<K>();
    if (law == nullptr) return;
    ++present;
    if constexpr (!std::is_void_v<typename PartBatch<Law>::type>) {
      if (PartBatch<Law>::type::applies(*law)) batched = K;
    }
  });
  return present == 1 ? batched : kParts;
}

}  // namespace

TouchingPull touching_pull(const CohesiveParts& parts, ContactList& contacts, double dt) {
  TouchingPull pull;
  const std::size_t batched = batched_part(parts);
  CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
    if constexpr (std::is_same_v<Law, LiquidBridge>) {
      if (K != batched || !PartBatch<Law>::type::kTouchingInPairLoop) return;
      pull = {contacts.state().data() + parts.offset_at(K), contacts.state_size(),
              parts.at<K>()->pair.f0_per_radius, dt};
    }
  });
  return pull;
}

namespace {

// Pass 1 over one block: batched by part `batched` (batched_part), or pair by pair.
void pass_one_block(const CohesiveParts& parts, std::size_t batched, const LiveTest& live,
                    const Particles& p, ContactList& contacts, double period, double dt,
                    std::size_t block, CohesionBuffers& buffers) {
  bool done = false;
  CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
    if constexpr (!std::is_void_v<typename PartBatch<Law>::type>) {
      if (K != batched) return;
      batched_block(*parts.at<K>(), parts.offset_at(K), p, contacts, period, dt, block, buffers);
      done = true;
    }
  });
  if (!done) cohesion_block(parts, live, p, contacts, period, dt, block, buffers);
}

// This step's events, for a replay across MPI ranks: the marked listed pairs and the dropped
// pairs whose state a part with events must settle, each with the liquid that ruptures (0: one
// forms), in the order the ordered pass meets them (listed, then dropped, each by (i, j)).
void list_events_of(const CohesiveParts& parts, const ContactList& contacts, std::size_t blocks,
                    CohesionBuffers& buffers) {
  buffers.events.clear();
  const auto row = contacts.row_start();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  for (std::size_t b = 0; b < blocks; ++b) {
    const CohesionBuffers::Entry* e = buffers.entries.data() + row[b * kCohesionBlockRows];
    for (const CohesionBuffers::Entry* last = e + buffers.count[b]; e != last; ++e) {
      if (e->event == 0) continue;
      buffers.events.push_back({e->i, e->j, event_liquid(parts, &state[e->k * stride])});
    }
  }
  const auto dropped = contacts.dropped();
  for (std::size_t q = 0; q < dropped.size(); ++q) {
    const double* s = &contacts.dropped_state()[q * stride];
    if (live_for_events(parts, s)) {
      buffers.events.push_back({dropped[q].i, dropped[q].j, event_liquid(parts, s)});
    }
  }
}

// The marked listed pairs of pass 1 (those with an event).
std::size_t marked_events(const ContactList& contacts, std::size_t blocks,
                          const CohesionBuffers& buffers) {
  std::size_t n = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    const CohesionBuffers::Entry* e =
        &buffers.entries[contacts.row_start()[b * kCohesionBlockRows]];
    for (std::size_t q = 0; q < buffers.count[b]; ++q) n += e[q].event;
  }
  return n;
}

// Dropped pair q's state settled by every part (a bridge's liquid back to the films).
void drop_pair(const CohesiveParts& parts, const ContactList& contacts, std::size_t q,
               double* film) {
  const IndexPair pair = contacts.dropped()[q];
  const double* ds = &contacts.dropped_state()[q * contacts.state_size()];
  parts.for_each([&](const auto& law, std::size_t off) {
    double s[std::remove_cvref_t<decltype(law)>::kStateSize];
    std::copy_n(ds + off, std::size(s), s);
    law.drop(s, film, pair.i, pair.j);
  });
}

// A decomposed run replays the events across ranks moving films only: no rupture sharing there.
void refuse_replayed(const RuptureSharing& sharing, const BridgeEventFilms* replay) {
  if (replay == nullptr || !sharing.active()) return;
  throw InputError(
      "liquid.rupture_to_bridges > 0 is not supported on a decomposed (MPI) run yet: the replay "
      "of bridge events across ranks moves films only (run drumlab, or set it to 0)");
}

// Dropped pair q settled: each part's drop, its liquid to the films, or with the rupture
// sharing ([liquid] rupture_to_bridges) to the particles' other bridges.
void settle_dropped_pair(const CohesiveParts& parts, const ContactList& contacts, std::size_t q,
                         double* film, RuptureSharing& sharing) {
  if (!sharing.active()) return drop_pair(parts, contacts, q, film);
  const IndexPair pair = contacts.dropped()[q];
  sharing.dropped(pair.i, pair.j,
                  event_liquid(parts, &contacts.dropped_state()[q * contacts.state_size()]));
  drop_pair(parts, contacts, q, nullptr);  // the state ends; its liquid is shared above
}

}  // namespace

void cohesion_pass_one(const CohesiveParts& parts, const Particles& p, ContactList& contacts,
                       double period, double dt, CohesionBuffers& buffers, bool list_events) {
  const std::size_t blocks = (contacts.rows() + kCohesionBlockRows - 1) / kCohesionBlockRows;
  if (buffers.mark.size() < contacts.size() || contacts.entry_rows().size() != contacts.size()) {
    throw std::logic_error("cohesive pass 1 before the pair loop's touch marks and entry rows");
  }
  if (buffers.entries.size() < contacts.size()) buffers.entries.resize(contacts.size());
  if (buffers.count.size() < blocks) buffers.count.resize(blocks);
  const auto n = static_cast<std::int64_t>(blocks);
  const std::size_t batched = batched_part(parts);
  const LiveTest live(parts);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < n; ++b) {
    pass_one_block(parts, batched, live, p, contacts, period, dt, static_cast<std::size_t>(b),
                   buffers);
  }
  if (list_events) list_events_of(parts, contacts, blocks, buffers);
}

void cohesion_ordered_pass(const CohesiveParts& parts, Particles& p, ContactList& contacts,
                           double period, double dt, const CohesionBuffers& buffers,
                           const BridgeEventFilms* replay) {
  const auto row = contacts.row_start();
  const std::size_t blocks = (contacts.rows() + kCohesionBlockRows - 1) / kCohesionBlockRows;
  double* film = film_of(parts, p);
  if (replay != nullptr && (film == nullptr || replay->before.size() != buffers.events.size())) {
    throw std::logic_error("bridge-event replay without films or of other events");
  }
  RuptureSharing sharing(parts, contacts, film, buffers.rupture);
  refuse_replayed(sharing, replay);
  // The listed events' places in buffers.events: the listed pairs' first, then the dropped ones'.
  std::size_t next_listed = 0;
  std::size_t next_dropped = replay != nullptr ? marked_events(contacts, blocks, buffers) : 0;
  // A decomposed run: whether event `at` runs on this rank, from the films of the serial pass.
  const auto run_here = [&](std::size_t at, Index i, Index j) {
    if (replay == nullptr) return true;
    const BridgeEventFilms::Before& b = replay->before[at];
    if (b.run) {
      film[i] = b.film_i;
      film[j] = b.film_j;
    }
    return b.run;
  };
  const auto dropped = contacts.dropped();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  std::size_t q = 0;
  // The dropped pairs before (i, j): beyond every part's range, so their state ends.
  const auto settle_dropped = [&](IndexPair until) {
    for (; q < dropped.size() && dropped[q] < until; ++q) {
      if (!live_for_events(parts, &contacts.dropped_state()[q * stride])) continue;
      if (run_here(next_dropped++, dropped[q].i, dropped[q].j)) {
        settle_dropped_pair(parts, contacts, q, film, sharing);
      }
    }
  };
  for (std::size_t b = 0; b < blocks; ++b) {
    const CohesionBuffers::Entry* e = buffers.entries.data() + row[b * kCohesionBlockRows];
    for (const CohesionBuffers::Entry* last = e + buffers.count[b]; e != last; ++e) {
      settle_dropped({e->i, e->j});
      Vec3 f = e->force;
      if (e->event != 0) {
        if (!run_here(next_listed++, e->i, e->j)) continue;
        const Vec3 d = nearest_image(p.position[e->i], p.position[e->j], period);
        const double dist = d.norm();
        const double gap = dist - (p.radius[e->i] + p.radius[e->j]);
        if (sharing.active()) sharing.listed(e->k, e->i, e->j, gap);
        const double pull =
            pair_attraction(parts, {p, e->i, e->j, d, dist, gap}, &state[e->k * stride], film, dt);
        if (pull == 0.0) continue;
        f = (pull / dist) * d;  // along i - j: attraction pulls i toward j
      }
      p.force[e->i] -= f;
      p.force[e->j] += f;
    }
  }
  constexpr Index kLast = std::numeric_limits<Index>::max();
  settle_dropped({kLast, kLast});
  contacts.clear_dropped();
  if (replay != nullptr) {
    for (const auto& [i, value] : replay->after) film[i] = value;
  }
}

void cohesion_wall_loop(const CohesiveParts& parts, Particles& p, std::span<const Index> candidates,
                        std::span<const std::uint8_t> near_parts, const Drum& drum, double omega,
                        double dt) {
  const std::size_t n_parts = drum.periodic() ? 1 : kWallParts;
  // Each registered part that acts at the wall (else nullptr), with the view of its per-particle
  // wall state.
  // (References, not a structured binding: clang 14 cannot capture those in the lambdas below.)
  auto law_and_wall = []<std::size_t... K>(std::index_sequence<K...>) {
    return std::pair{std::tuple<const LawOf<K>*...>{},
                     std::tuple<typename LawOf<K>::WallState...>{}};
  }
  (std::make_index_sequence<kParts>{});
  auto& law = law_and_wall.first;
  auto& wall = law_and_wall.second;
  bool any = false;
  CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
    const Law* part = parts.at<K>();
    if (part == nullptr || !part->acts_at_wall()) return;
    std::get<K>(law) = part;
    std::get<K>(wall) = part->wall_state(p, n_parts);
    any = true;
  });
  if (!any) return;
  double* film = film_of(parts, p);
  const auto count = static_cast<std::int64_t>(candidates.size());
#pragma omp parallel
  {
    const auto acting = law;  // each thread's copies: pointers kept in registers
    auto state = wall;
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < count; ++c) {
      const Index i = candidates[static_cast<std::size_t>(c)];
      const Vec3& x = p.position[i];
      const double r = p.radius[i];
      const unsigned near = near_parts.empty() ? ~0u : near_parts[static_cast<std::size_t>(c)];
      for (std::size_t w = 0; w < n_parts; ++w) {
        if (((near >> w) & 1u) == 0) continue;  // beyond every link since the last build
        const WallGap g = wall_gap(drum, static_cast<WallPart>(w), x, r);
        bool live = false;
        CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
          const Law* part = std::get<K>(acting);
          live = live || (part != nullptr && part->wall_live(std::get<K>(state), i, w));
        });
        if (g.gap > 0.0 && !live) continue;  // nothing acts
        double pull = 0.0;
        const WallSite site{p, i, w, g, omega};
        CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
          const Law* part = std::get<K>(acting);
          if (part != nullptr) part->advance_wall(std::get<K>(state), site, film, dt, pull);
        });
        if (pull != 0.0) p.force[i] -= pull * g.normal;  // the normal points into the particle
      }
    }
  }
}

void cohesion_bonds(const CohesiveParts& parts, const Particles& p, const ContactList& contacts,
                    double period, std::vector<Bond>& out) {
  out.clear();
  std::array<bool, kParts> bonds{};
  CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
    bonds[K] = parts.at<K>() != nullptr && parts.at<K>()->bonds();
  });
  if (std::find(bonds.begin(), bonds.end(), true) == bonds.end()) return;
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  const auto bonded = [&]<std::size_t K>(const double* s) {
    return bonds[K] && LawOf<K>::bonded(s + parts.offset_at(K));
  };
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const double* s = &state[k * stride];
      bool any = false;
      CohesiveParts::for_each_law(
          [&]<std::size_t K, class Law>() { any = any || bonded.template operator()<K>(s); });
      if (!any) continue;
      const Index j = col[k];
      const Vec3 d = nearest_image(p.position[i], p.position[j], period);
      const double dist = d.norm();
      const PairGap g{p, static_cast<Index>(i), j, d, dist, dist - (p.radius[i] + p.radius[j])};
      Bond bond{static_cast<Index>(i), j, 0.0, 0.0, 0.0};
      bool first = true;
      CohesiveParts::for_each_law([&]<std::size_t K, class Law>() {
        if (!bonded.template operator()<K>(s)) return;
        const BondShare share = parts.at<K>()->bond_share(g, s + parts.offset_at(K));
        bond.volume += share.volume;
        bond.force += share.force;
        if (first) bond.age = share.age;
        first = false;
      });
      out.push_back(bond);
    }
  }
}

LiquidTotals liquid_totals(const CohesiveParts& parts, const Particles& p,
                           const ContactList& contacts, std::span<const std::uint8_t> ghost) {
  LiquidTotals t;
  bool holds = false;
  parts.for_each([&](const auto& law, std::size_t) {
    holds = holds || std::remove_cvref_t<decltype(law)>::kHoldsLiquid;
  });
  if (!holds) return t;
  const auto skip = [&](std::size_t i) { return !ghost.empty() && ghost[i] != 0; };
  if (const std::vector<double>* film = p.find_array(kLiquidFilmArray)) {
    for (std::size_t i = 0; i < film->size(); ++i) {
      if (!skip(i)) t.films += (*film)[i];
    }
  }
  const auto row = contacts.row_start();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    if (skip(i)) continue;
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      parts.for_each([&](const auto& law, std::size_t off) {
        if constexpr (std::remove_cvref_t<decltype(law)>::kHoldsLiquid) {
          const double v = law.liquid(&state[k * stride + off]);
          t.bridges += v;
          t.bridge_count += v > 0.0;
        }
      });
    }
  }
  for (std::size_t w = 0; w < kWallParts; ++w) {
    const std::vector<double>* v = p.find_array(kWallBridgeVolumeArrays[w]);
    if (v == nullptr) continue;
    for (std::size_t i = 0; i < v->size(); ++i) t.wall_bridge_count += !skip(i) && (*v)[i] > 0.0;
  }
  t.wall_bridges = wall_bridge_liquid(p, ghost);
  return t;
}

double wall_bridge_liquid(const Particles& p, std::span<const std::uint8_t> ghost) {
  double sum = 0.0;
  for (std::size_t w = 0; w < kWallParts; ++w) {
    const std::vector<double>* v = p.find_array(kWallBridgeVolumeArrays[w]);
    if (v == nullptr) continue;
    for (std::size_t i = 0; i < v->size(); ++i) {
      if (ghost.empty() || ghost[i] == 0) sum += (*v)[i];
    }
  }
  return sum;
}

}  // namespace drumlab
