#include "engine/parallel/mpi/mpi_bridge_events.hpp"

#include <algorithm>
#include <stdexcept>

#include "engine/parallel/particle_pack.hpp"

namespace drumlab {

void MpiBridgeEvents::gather(const LiquidBridge& bridge, std::span<const BridgeEvent> events,
                             const double* film) {
  // This rank's message: its events whose first particle it owns (the serial pass's slots), then
  // the films of its owned particles in any of its events (as they stand before the pass).
  std::vector<SlotEvent> mine;
  std::vector<Index> touched;
  for (const BridgeEvent& e : events) {
    if (owned(e.i)) mine.push_back({slot_[e.i], slot_[e.j], e.volume, film[e.i], film[e.j]});
    for (const Index x : {e.i, e.j}) {
      if (owned(x)) touched.push_back(x);
    }
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  std::vector<std::byte> msg;
  put_bytes(msg, static_cast<std::uint64_t>(mine.size()));
  put_bytes(msg, static_cast<std::uint64_t>(touched.size()));
  for (const SlotEvent& e : mine) put_bytes(msg, e);
  for (const Index x : touched) put_bytes(msg, SlotFilm{slot_[x], film[x]});
  const std::vector<std::byte> all = comm_.all_gather(std::span<const std::byte>(msg));
  std::vector<SlotEvent> gathered;
  std::vector<SlotFilm> films;
  const std::span<const std::byte> in(all);
  for (std::size_t pos = 0; pos < in.size();) {
    const auto n = get_bytes<std::uint64_t>(in, pos);
    const auto m = get_bytes<std::uint64_t>(in, pos);
    for (std::uint64_t k = 0; k < n; ++k) gathered.push_back(get_bytes<SlotEvent>(in, pos));
    for (std::uint64_t k = 0; k < m; ++k) films.push_back(get_bytes<SlotFilm>(in, pos));
  }
  replay_.run(bridge, std::move(gathered), std::move(films));
  replayed_ += replay_.size();
}

void MpiBridgeEvents::replay(const LiquidBridge& bridge, std::span<const BridgeEvent> events,
                             const double* film, BridgeEventFilms& out) {
  if (ghost_ == nullptr) throw std::logic_error("MpiBridgeEvents: no ghost mask");
  gather(bridge, events, film);
  out.before.clear();
  for (const BridgeEvent& e : events) {
    BridgeEventFilms::Before b;
    // A pair of two ghosts: its force is discarded and its films come from `after`.
    if (owned(e.i) || owned(e.j)) {
      if (const std::pair<double, double>* f = replay_.before(slot_[e.i], slot_[e.j])) {
        b = {true, f->first, f->second};
      }
    }
    out.before.push_back(b);
  }
  out.after.clear();
  for (const SlotFilm& f : replay_.films()) {
    const auto it = std::lower_bound(slot_.begin(), slot_.end(), f.slot);
    if (it != slot_.end() && *it == f.slot) {
      out.after.emplace_back(static_cast<Index>(it - slot_.begin()), f.film);
    }
  }
}

}  // namespace drumlab
