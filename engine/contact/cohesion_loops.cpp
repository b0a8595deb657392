#include "engine/contact/cohesion_loops.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "engine/contact/bridge_batch.hpp"
#include "engine/periodic.hpp"

namespace drumlab {
namespace {

double* film_of(const CohesiveParts& parts, Particles& p) {
  if (parts.bridge == nullptr || !parts.bridge->migration) return nullptr;
  std::vector<double>* film = p.find_array(kLiquidFilmArray);
  if (film == nullptr) throw std::logic_error("liquid migration without a film array");
  return film->data();
}

// 1 if a cohesive part may act on a listed pair with touch mark `mark` (touch_mark): touching,
// or `live` (a bridge or an adhesive contact holds), and with distinct centres.
[[gnu::always_inline]] inline std::size_t take(std::uint8_t mark, bool live) {
  const unsigned m = mark;
  return ((m & kTouchOrEqual) | static_cast<unsigned>(live)) & (m >> 1);
}

// A bridge between i and j ends: its liquid goes back, half to each film (migration).
void rupture(double* state, double* film, Index i, Index j) {
  if (film != nullptr) {
    film[i] += 0.5 * state[0];
    film[j] += 0.5 * state[0];
  }
  state[0] = 0.0;
  state[1] = 0.0;
}

// One listed pair at centre separation d (i - j): advances its state, returns the attraction
// (N, > 0 pulls i towards j).
double pair_attraction(const CohesiveParts& parts, Particles& p, double* film, Index i, Index j,
                       const Vec3& d, double dist, double* state, double dt) {
  const double r_i = p.radius[i];
  const double r_j = p.radius[j];
  const double gap = dist - (r_i + r_j);
  double pull = 0.0;
  if (const LiquidBridge* b = parts.bridge) {
    double* s = state + parts.bridge_offset;
    if (s[0] > 0.0 && b->pair.ruptured(gap, s[0])) {
      rupture(s, film, i, j);
    }
    if (s[0] > 0.0) {
      s[1] += dt;
    } else if (gap <= 0.0) {
      double none = 0.0;
      const double v =
          film != nullptr ? b->take_from_films(film[i], film[j]) : b->take_from_films(none, none);
      s[0] = v;
      s[1] = 0.0;
    }
    if (s[0] > 0.0) {
      pull += b->pair.force(gap, LiquidBridge::pair_radius(r_i, r_j), s[0]);
      if (b->viscosity > 0.0) {
        const double vn = (p.velocity[i] - p.velocity[j]).dot(d) / dist;
        pull -= b->viscous_force(gap, r_i * r_j / (r_i + r_j), vn);
      }
    }
  }
  if (const SjkrCohesion* c = parts.sjkr) {
    double* s = state + parts.sjkr_offset;
    if (gap < 0.0) {
      pull += c->force(SjkrCohesion::lens_area(dist, r_i, r_j));
      s[1] = s[0] > 0.0 ? s[1] + dt : 0.0;
      s[0] = 1.0;
    } else {
      s[0] = 0.0;
      s[1] = 0.0;
    }
  }
  return pull;
}

// True if the pair's bridge forms or ruptures at this step (its films change): with a bridge
// beyond its rupture distance, or touching without one (MercuryDPM's form()/rupture()).
bool bridge_event(const CohesiveParts& parts, const double* state, double gap) {
  const LiquidBridge* b = parts.bridge;
  if (b == nullptr) return false;
  const double v = state[parts.bridge_offset];
  return v > 0.0 ? b->pair.ruptured(gap, v) : gap <= 0.0;
}

// The force of listed pair k (i, j) without a bridge event (its state advanced), or a marked
// entry if it has one; nothing if no part acts on it.
[[gnu::always_inline]] inline void cohesion_entry(const CohesiveParts& parts, Particles& p,
                                                  double* st, Index i, Index j, std::size_t k,
                                                  const Vec3& d, double dt,
                                                  CohesionBuffers::Entry* out, std::size_t& n) {
  const double dist = d.norm();
  const auto kk = static_cast<std::uint32_t>(k);
  if (bridge_event(parts, st, dist - (p.radius[i] + p.radius[j]))) {
    out[n++] = {i, j, kk, 1, Vec3::Zero()};
    return;
  }
  const double pull = pair_attraction(parts, p, nullptr, i, j, d, dist, st, dt);
  if (pull != 0.0) out[n++] = {i, j, kk, 0, (pull / dist) * d};
}

// Visits, by increasing k, the listed pairs of the rows of cohesion block `block` on which a
// cohesive part may act: take(mark[k], live(k)). Most listed pairs are apart, with no bridge and
// no adhesive contact: nothing acts (a bridge forms only on contact; sjkr acts only while
// overlapping). Each chunk of a row is first sifted by a loop without branches on the touch
// marks the contact pair loop left (no partner is gathered for it), then visit(i, k) runs on the
// pairs that remain.
template <class Live, class Visit>
[[gnu::always_inline]] inline void for_each_acting_pair(const ContactList& contacts,
                                                        const std::uint8_t* mark, std::size_t block,
                                                        Live&& live, Visit&& visit) {
  constexpr std::size_t kChunk = 64;
  std::uint32_t sel[kChunk];
  const auto row = contacts.row_start();
  const std::size_t begin = block * kCohesionBlockRows;
  const std::size_t end = std::min(contacts.rows(), begin + kCohesionBlockRows);
  for (std::size_t i = begin; i < end; ++i) {
    for (std::size_t k0 = row[i]; k0 < row[i + 1]; k0 += kChunk) {
      const std::size_t k1 = std::min(row[i + 1], k0 + kChunk);
      std::size_t m = 0;
      for (std::size_t k = k0; k < k1; ++k) {
        sel[m] = static_cast<std::uint32_t>(k - k0);
        m += take(mark[k], live(k));
      }
      for (std::size_t q = 0; q < m; ++q) visit(i, k0 + sel[q]);
    }
  }
}

// Pass 1 of cohesion_pair_loop over the rows of block `block`, any composition of parts: every
// pair that may act (for_each_acting_pair) evaluated one at a time.
[[gnu::noinline]] void cohesion_block(const CohesiveParts& parts, Particles& p,
                                      ContactList& contacts, double period, double dt,
                                      std::size_t block, CohesionBuffers& buffers) {
  const auto col = contacts.col();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  const bool bridges = parts.bridge != nullptr;
  const bool sjkr = parts.sjkr != nullptr;
  const std::size_t bo = parts.bridge_offset, so = parts.sjkr_offset;  // < stride
  CohesionBuffers::Entry* out = &buffers.entries[contacts.row_start()[block * kCohesionBlockRows]];
  std::size_t n = 0;
  for_each_acting_pair(
      contacts, buffers.mark.data(), block,
      [&](std::size_t k) {
        const double* st = &state[k * stride];
        return (bridges & (st[bo] > 0.0)) | (sjkr & (st[so] > 0.0));
      },
      [&](std::size_t i, std::size_t k) {
        const Index j = col[k];
        cohesion_entry(parts, p, &state[k * stride], static_cast<Index>(i), j, k,
                       nearest_image(p.position[i], p.position[j], period), dt, out, n);
      });
  buffers.count[block] = n;
}

// Pass 1 over block `block` for a scene whose only cohesive part is the plain bridge (no viscous
// term, no sjkr): the same entries as cohesion_block, in the same order; the pairs that may act
// (touching, or bridged) are evaluated in a BridgeBatch's SIMD lanes (bridge_batch.hpp).
[[gnu::noinline]] void bridge_block(const LiquidBridge& bridge, std::size_t bo, Particles& p,
                                    ContactList& contacts, double period, double dt,
                                    std::size_t block, CohesionBuffers& buffers) {
  const auto col = contacts.col();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  CohesionBuffers::Entry* out = &buffers.entries[contacts.row_start()[block * kCohesionBlockRows]];
  std::size_t n = 0;
  BridgeBatch batch;
  const auto flush = [&] {
    batch.evaluate(bridge.pair);
    for (std::size_t l = 0; l < batch.count; ++l) {
      if (batch.kind[l] == BridgeBatch::kNothing) continue;
      bool event = batch.kind[l] == BridgeBatch::kEvent;
      if (event && batch.volume[l] > 0.0) {
        event = bridge.pair.ruptured(batch.gaps[l], batch.volume[l]);  // within 1e-6 of s_rup
      }
      if (!event) state[batch.k[l] * stride + bo + 1] += dt;  // the bridge ages
      out[n++] = {batch.i[l], batch.j[l], batch.k[l], event ? 1u : 0u,
                  event ? Vec3::Zero() : batch.force.vec3(l)};
    }
    batch.count = 0;
  };
  for_each_acting_pair(
      contacts, buffers.mark.data(), block,
      [&](std::size_t k) { return state[k * stride + bo] > 0.0; },
      [&](std::size_t i, std::size_t k) {
        const Index j = col[k];
        batch.add(static_cast<Index>(i), j, static_cast<std::uint32_t>(k),
                  nearest_image(p.position[i], p.position[j], period), p.radius[i], p.radius[j],
                  state[k * stride + bo]);
        if (batch.full()) flush();
      });
  flush();
  buffers.count[block] = n;
}

// This step's bridge events, for a decomposed run's hooks: the marked listed pairs and the
// dropped pairs with a bridge, each with the volume that ruptures (0: a bridge forms).
void list_bridge_events(const CohesiveParts& parts, const ContactList& contacts, std::size_t blocks,
                        CohesionBuffers& buffers) {
  buffers.events.clear();
  const auto row = contacts.row_start();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  for (std::size_t b = 0; b < blocks; ++b) {
    const CohesionBuffers::Entry* e = &buffers.entries[row[b * kCohesionBlockRows]];
    for (const CohesionBuffers::Entry* last = e + buffers.count[b]; e != last; ++e) {
      if (e->event == 0) continue;
      buffers.events.push_back({e->i, e->j, state[e->k * stride + parts.bridge_offset]});
    }
  }
  const auto dropped = contacts.dropped();
  for (std::size_t q = 0; q < dropped.size(); ++q) {
    const double v = contacts.dropped_state()[q * stride + parts.bridge_offset];
    if (v > 0.0) buffers.events.push_back({dropped[q].i, dropped[q].j, v});
  }
}

}  // namespace

WallGap wall_gap(const Drum& drum, WallPart part, const Vec3& x, double r) {
  if (part == WallPart::cap_low) return {x.z() - r, Vec3(0.0, 0.0, 1.0)};
  if (part == WallPart::cap_high) return {drum.depth() - x.z() - r, Vec3(0.0, 0.0, -1.0)};
  const double rho = std::sqrt(x.x() * x.x() + x.y() * x.y());
  if (rho == 0.0) return {drum.radius() - r, Vec3::Zero()};
  return {drum.radius() - rho - r, Vec3(-x.x() / rho, -x.y() / rho, 0.0)};
}

void cohesion_pair_loop(const CohesiveParts& parts, Particles& p, ContactList& contacts,
                        double period, double dt, CohesionBuffers& buffers) {
  const auto row = contacts.row_start();
  const std::size_t blocks = (contacts.rows() + kCohesionBlockRows - 1) / kCohesionBlockRows;
  if (buffers.entries.size() < contacts.size()) buffers.entries.resize(contacts.size());
  if (buffers.count.size() < blocks) buffers.count.resize(blocks);
  const auto n = static_cast<std::int64_t>(blocks);
  const bool plain_bridge =
      parts.bridge != nullptr && parts.sjkr == nullptr && parts.bridge->viscosity == 0.0;
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < n; ++b) {
    const auto block = static_cast<std::size_t>(b);
    if (plain_bridge) {
      bridge_block(*parts.bridge, parts.bridge_offset, p, contacts, period, dt, block, buffers);
    } else {
      cohesion_block(parts, p, contacts, period, dt, block, buffers);
    }
  }
  double* film = film_of(parts, p);
  // A decomposed run: each event below starts from the films the serial pass would give it (every
  // rank takes part, with or without particles).
  BridgeEventHooks* hooks =
      parts.bridge != nullptr && parts.bridge->migration ? buffers.hooks : nullptr;
  if (hooks != nullptr) {
    list_bridge_events(parts, contacts, blocks, buffers);
    hooks->begin(*parts.bridge, buffers.events, film);
  }
  const auto dropped = contacts.dropped();
  const auto dropped_state = contacts.dropped_state();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  std::size_t q = 0;
  // The dropped pairs before (i, j): beyond every rupture distance, so their bridges end.
  const auto settle_dropped = [&](IndexPair until) {
    for (; q < dropped.size() && dropped[q] < until; ++q) {
      if (parts.bridge == nullptr) continue;
      double s[LiquidBridge::kStateSize] = {dropped_state[q * stride + parts.bridge_offset], 0.0};
      if (!(s[0] > 0.0)) continue;
      if (hooks == nullptr || hooks->before(dropped[q].i, dropped[q].j, film)) {
        rupture(s, film, dropped[q].i, dropped[q].j);
      }
    }
  };
  for (std::size_t b = 0; b < blocks; ++b) {
    const CohesionBuffers::Entry* e = &buffers.entries[row[b * kCohesionBlockRows]];
    for (const CohesionBuffers::Entry* last = e + buffers.count[b]; e != last; ++e) {
      settle_dropped({e->i, e->j});
      Vec3 f = e->force;
      if (e->event != 0) {
        if (hooks != nullptr && !hooks->before(e->i, e->j, film)) continue;
        const Vec3 d = nearest_image(p.position[e->i], p.position[e->j], period);
        const double dist = d.norm();
        const double pull =
            pair_attraction(parts, p, film, e->i, e->j, d, dist, &state[e->k * stride], dt);
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
  if (hooks != nullptr) hooks->end(film);
}

void cohesion_wall_loop(const CohesiveParts& parts, Particles& p, std::span<const Index> candidates,
                        const Drum& drum, double omega, double dt) {
  const LiquidBridge* b =
      parts.bridge != nullptr && parts.bridge->wall_bridges ? parts.bridge : nullptr;
  if (b == nullptr && parts.sjkr == nullptr) return;
  const std::size_t n_parts = drum.periodic() ? 1 : kWallParts;
  double* film = film_of(parts, p);
  double* volume[kWallParts] = {};
  double* age[kWallParts] = {};
  if (b != nullptr) {
    for (std::size_t w = 0; w < n_parts; ++w) {
      std::vector<double>* v = p.find_array(kWallBridgeVolumeArrays[w]);
      std::vector<double>* a = p.find_array(kWallBridgeAgeArrays[w]);
      if (v == nullptr || a == nullptr) throw std::logic_error("wall bridges without arrays");
      volume[w] = v->data();
      age[w] = a->data();
    }
  }
  const auto count = static_cast<std::int64_t>(candidates.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t q = 0; q < count; ++q) {
    const Index i = candidates[static_cast<std::size_t>(q)];
    const Vec3& x = p.position[i];
    const double r = p.radius[i];
    for (std::size_t w = 0; w < n_parts; ++w) {
      const WallGap g = wall_gap(drum, static_cast<WallPart>(w), x, r);
      if (g.gap > 0.0 && (b == nullptr || !(volume[w][i] > 0.0))) continue;  // nothing acts
      double pull = 0.0;
      if (b != nullptr) {
        double& v = volume[w][i];
        if (v > 0.0 && b->wall.ruptured(g.gap, v)) {
          if (film != nullptr) film[i] += v;
          v = 0.0;
          age[w][i] = 0.0;
        }
        if (v > 0.0) {
          age[w][i] += dt;
        } else if (g.gap <= 0.0) {
          double none = 0.0;
          v = b->take_from_film(film != nullptr ? film[i] : none);
          age[w][i] = 0.0;
        }
        if (v > 0.0) {
          pull += b->wall.force(g.gap, LiquidBridge::wall_radius(r), v);
          if (b->viscosity > 0.0) {
            const Vec3 point = x - (r + std::max(g.gap, 0.0)) * g.normal;
            const double vn = (p.velocity[i] - Drum::wall_velocity(point, omega)).dot(g.normal);
            pull -= b->viscous_force(g.gap, r, vn);
          }
        }
      }
      if (parts.sjkr != nullptr && g.gap < 0.0) {
        pull += parts.sjkr->force(SjkrCohesion::wall_lens_area(-g.gap, r));
      }
      if (pull != 0.0) p.force[i] -= pull * g.normal;  // the normal points into the particle
    }
  }
}

void cohesion_bonds(const CohesiveParts& parts, const Particles& p, const ContactList& contacts,
                    double period, std::vector<Bond>& out) {
  out.clear();
  const bool adhesive = parts.sjkr != nullptr && parts.sjkr->energy_density > 0.0;
  if (parts.bridge == nullptr && !adhesive) return;
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const double* s = &state[k * stride];
      const double* sb = parts.bridge != nullptr ? s + parts.bridge_offset : nullptr;
      const double* sc = adhesive ? s + parts.sjkr_offset : nullptr;
      const bool bridged = sb != nullptr && LiquidBridge::bond(sb);
      const bool stuck = sc != nullptr && SjkrCohesion::bond(sc);
      if (!bridged && !stuck) continue;
      const Index j = col[k];
      const double dist = nearest_image(p.position[i], p.position[j], period).norm();
      const double r_i = p.radius[i];
      const double r_j = p.radius[j];
      Bond bond{static_cast<Index>(i), j, 0.0, 0.0, 0.0};
      if (bridged) {
        bond.volume = LiquidBridge::bond_volume(sb);
        bond.force = parts.bridge->pair.force(dist - (r_i + r_j),
                                              LiquidBridge::pair_radius(r_i, r_j), bond.volume);
        bond.age = LiquidBridge::bond_age(sb);
      }
      if (stuck) {
        bond.force += parts.sjkr->force(SjkrCohesion::lens_area(dist, r_i, r_j));
        if (!bridged) bond.age = SjkrCohesion::bond_age(sc);
      }
      out.push_back(bond);
    }
  }
}

void seed_bridges(const CohesiveParts& parts, Particles& p, ContactList& contacts, double period,
                  std::vector<double>& reserve) {
  double* film = film_of(parts, p);
  if (film == nullptr || reserve.size() != p.size()) throw std::logic_error("no films to seed");
  const auto row = contacts.row_start();
  const auto col = contacts.col();
  const auto state = contacts.state();
  const std::size_t stride = contacts.state_size();
  const auto touching = [&](std::size_t i, Index j) {
    const double dist = nearest_image(p.position[i], p.position[j], period).norm();
    return dist > 0.0 && dist <= p.radius[i] + p.radius[j];
  };
  std::vector<double> share(p.size(), 0.0);
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      if (!touching(i, col[k])) continue;
      share[i] += 1.0;
      share[col[k]] += 1.0;
    }
  }
  for (std::size_t i = 0; i < share.size(); ++i) {
    share[i] = share[i] > 0.0 ? reserve[i] / share[i] : 0.0;
  }
  const double v_max = parts.bridge->max_volume;
  for (std::size_t i = 0; i < contacts.rows(); ++i) {
    for (std::size_t k = row[i]; k < row[i + 1]; ++k) {
      const Index j = col[k];
      if (!touching(i, j)) continue;
      double gi = share[i], gj = share[j];
      if (gi + gj > v_max) {
        gi = share[i] * (v_max / (share[i] + share[j]));
        gj = v_max - gi;
      }
      if (!(gi + gj > 0.0)) continue;
      double* s = &state[k * stride + parts.bridge_offset];
      s[0] = gi + gj;
      s[1] = 0.0;
      reserve[i] -= gi;
      reserve[j] -= gj;
    }
  }
  for (std::size_t i = 0; i < reserve.size(); ++i) film[i] += reserve[i];
  reserve.clear();
}

std::vector<std::string_view> liquid_array_names(const LiquidBridge& bridge,
                                                 std::size_t wall_parts) {
  std::vector<std::string_view> names;
  if (bridge.migration) names.push_back(kLiquidFilmArray);
  if (!bridge.wall_bridges) return names;
  for (std::size_t w = 0; w < wall_parts; ++w) {
    names.push_back(kWallBridgeVolumeArrays[w]);
    names.push_back(kWallBridgeAgeArrays[w]);
  }
  return names;
}

void fill_films(const LiquidConfig& liquid, Particles& p, std::vector<double>& reserve) {
  std::vector<double>* film = p.find_array(kLiquidFilmArray);
  if (film == nullptr) throw std::logic_error("fill_films: no film array");
  reserve.assign(p.size(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    const double v = liquid.liquid_content * (4.0 / 3.0) * std::numbers::pi * r * r * r;
    (*film)[i] = liquid.film_share * v;
    reserve[i] = v - (*film)[i];
  }
  if (liquid.film_share == 1.0) reserve.clear();
}

LiquidTotals liquid_totals(const CohesiveParts& parts, const Particles& p,
                           const ContactList& contacts, std::span<const std::uint8_t> ghost) {
  LiquidTotals t;
  if (parts.bridge == nullptr) return t;
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
      const double v = state[k * stride + parts.bridge_offset];
      t.bridges += v;
      t.bridge_count += v > 0.0;
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
