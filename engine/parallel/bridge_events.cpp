#include "engine/parallel/bridge_events.hpp"

#include <algorithm>
#include <stdexcept>

namespace drumlab {

namespace {

bool by_pair(const SlotEvent& x, const SlotEvent& y) {
  return x.a != y.a ? x.a < y.a : x.b < y.b;
}

bool by_slot(const SlotFilm& x, const SlotFilm& y) {
  return x.slot < y.slot;
}

double& film_at(std::vector<SlotFilm>& films, std::uint64_t slot) {
  const auto it = std::lower_bound(films.begin(), films.end(), SlotFilm{slot, 0.0}, by_slot);
  if (it == films.end() || it->slot != slot) throw std::logic_error("BridgeReplay: no film");
  return it->film;
}

}  // namespace

void BridgeReplay::run(const LiquidBridge& bridge, std::vector<SlotEvent> events,
                       std::vector<SlotFilm> films) {
  std::sort(events.begin(), events.end(), by_pair);
  std::stable_sort(films.begin(), films.end(), by_slot);
  films.erase(std::unique(films.begin(), films.end(),
                          [](const SlotFilm& x, const SlotFilm& y) { return x.slot == y.slot; }),
              films.end());
  // A particle whose owner sent no film (not expected: its owner lists the pair too) takes the
  // lister's copy.
  const std::size_t owned = films.size();
  for (const SlotEvent& e : events) {
    for (const auto& [slot, film] : {std::pair{e.a, e.film_a}, std::pair{e.b, e.film_b}}) {
      if (!std::binary_search(films.begin(), films.begin() + static_cast<std::ptrdiff_t>(owned),
                              SlotFilm{slot, 0.0}, by_slot)) {
        films.push_back({slot, film});
      }
    }
  }
  std::stable_sort(films.begin(), films.end(), by_slot);
  films.erase(std::unique(films.begin(), films.end(),
                          [](const SlotFilm& x, const SlotFilm& y) { return x.slot == y.slot; }),
              films.end());
  before_.resize(events.size());
  for (std::size_t k = 0; k < events.size(); ++k) {
    double& fa = film_at(films, events[k].a);
    double& fb = film_at(films, events[k].b);
    before_[k] = {fa, fb};
    if (events[k].volume > 0.0) {  // cohesion_loops.cpp's rupture(): half back to each film
      fa += 0.5 * events[k].volume;
      fb += 0.5 * events[k].volume;
    } else {
      bridge.take_from_films(fa, fb);
    }
  }
  events_ = std::move(events);
  films_ = std::move(films);
}

const std::pair<double, double>* BridgeReplay::before(std::uint64_t a, std::uint64_t b) const {
  const SlotEvent key{a, b, 0.0, 0.0, 0.0};
  const auto it = std::lower_bound(events_.begin(), events_.end(), key, by_pair);
  if (it == events_.end() || it->a != a || it->b != b) return nullptr;
  return &before_[static_cast<std::size_t>(it - events_.begin())];
}

}  // namespace drumlab
