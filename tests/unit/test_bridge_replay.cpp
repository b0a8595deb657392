// BridgeReplay (engine/parallel/bridge_events.hpp), the serial half of the liquid's migration
// across MPI ranks: the ranks' events, in any order, replayed in the serial order (a, b) on the
// owners' films give every event the films it would see in one pass and every film its end value;
// checked against that one pass over an array of films, and for the liquid's conservation.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/parallel/bridge_events.hpp"

namespace drumlab {
namespace {

LiquidBridge migrating_bridge() {
  LiquidBridge b;
  b.migration = true;
  b.max_volume = 1.0;
  return b;
}

TEST(BridgeReplay, ShuffledEventsGiveTheFilmsOfOnePassInTheSerialOrder) {
  const LiquidBridge bridge = migrating_bridge();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 0.8);
  constexpr std::uint64_t kSlots = 12;
  std::vector<double> film(kSlots);
  for (double& f : film) f = u(rng);
  // Chains: every slot in several events, formations and ruptures (volume > 0), pairs a < b.
  std::vector<SlotEvent> events;
  for (std::uint64_t a = 0; a < kSlots; ++a) {
    for (std::uint64_t b = a + 1; b < kSlots; b += 1 + a % 3) {
      events.push_back({a, b, (a + b) % 2 == 0 ? u(rng) : 0.0, -1.0, -1.0});
    }
  }
  // The oracle: one pass in (a, b) order over the array, as cohesion_ordered_pass runs the events.
  std::vector<double> want = film;
  std::vector<std::pair<double, double>> seen;
  double formed = 0.0, ruptured = 0.0;
  for (const SlotEvent& e : events) {
    seen.emplace_back(want[e.a], want[e.b]);
    if (e.volume > 0.0) {
      want[e.a] += 0.5 * e.volume;
      want[e.b] += 0.5 * e.volume;
      ruptured += e.volume;
    } else {
      formed += bridge.take_from_films(want[e.a], want[e.b]);
    }
  }
  std::vector<SlotFilm> films;
  for (std::uint64_t s = 0; s < kSlots; ++s) {
    films.push_back({s, film[s]});
    if (s % 3 == 0) films.push_back({s, film[s]});  // sent by two ranks
  }
  std::vector<SlotEvent> shuffled = events;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  std::shuffle(films.begin(), films.end(), rng);
  BridgeReplay r;
  r.run(bridge, shuffled, films);
  ASSERT_EQ(r.size(), events.size());
  for (std::size_t k = 0; k < events.size(); ++k) {
    const auto* f = r.before(events[k].a, events[k].b);
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->first, seen[k].first) << k;
    EXPECT_EQ(f->second, seen[k].second) << k;
  }
  EXPECT_EQ(r.before(1, 3), nullptr);  // a = 1 pairs with 2, 4, 6, ... only
  EXPECT_EQ(r.before(5, 100), nullptr);
  ASSERT_EQ(r.films().size(), kSlots);
  double before = 0.0, after = 0.0;
  for (std::uint64_t s = 0; s < kSlots; ++s) {
    EXPECT_EQ(r.films()[s].slot, s);
    EXPECT_EQ(r.films()[s].film, want[s]) << s;
    before += film[s];
    after += r.films()[s].film;
  }
  EXPECT_NEAR(after + formed - ruptured, before, 1e-14);  // liquid conserved
}

TEST(BridgeReplay, AParticleWithoutItsOwnersFilmTakesTheListersCopy) {
  const LiquidBridge bridge = migrating_bridge();
  BridgeReplay r;
  // Slot 7's owner sent nothing; slot 3's owner sent 0.25 (the lister's copy 0.9 is not used).
  r.run(bridge, {{3, 7, 0.0, 0.9, 0.125}}, {{3, 0.25}});
  const auto* f = r.before(3, 7);
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->first, 0.25);
  EXPECT_EQ(f->second, 0.125);
  ASSERT_EQ(r.films().size(), 2u);
  EXPECT_EQ(r.films()[0].film, 0.0);  // both films into the new bridge (0.375 <= V_max)
  EXPECT_EQ(r.films()[1].film, 0.0);
}

}  // namespace
}  // namespace drumlab
