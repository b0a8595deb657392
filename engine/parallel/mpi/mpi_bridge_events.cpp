#include "engine/parallel/mpi/mpi_bridge_events.hpp"

#include <algorithm>
#include <stdexcept>

#include "engine/parallel/particle_pack.hpp"

namespace drumlab {

void MpiBridgeEvents::begin(const LiquidBridge& bridge, std::span<const Event> events,
                            const double* film) {
  if (ghost_ == nullptr) throw std::logic_error("MpiBridgeEvents: no ghost mask");
  // This rank's message: its events whose first particle it owns (the serial pass's slots), then
  // the films of its owned particles in any of its events (as they stand before the pass).
  std::vector<SlotEvent> mine;
  std::vector<Index> touched;
  for (const Event& e : events) {
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

bool MpiBridgeEvents::before(Index i, Index j, double* film) {
  // A pair of two ghosts: its force is discarded and its films come from end().
  if (!owned(i) && !owned(j)) return false;
  const std::pair<double, double>* f = replay_.before(slot_[i], slot_[j]);
  if (f == nullptr) return false;
  film[i] = f->first;
  film[j] = f->second;
  return true;
}

void MpiBridgeEvents::end(double* film) {
  for (const SlotFilm& f : replay_.films()) {
    const auto it = std::lower_bound(slot_.begin(), slot_.end(), f.slot);
    if (it != slot_.end() && *it == f.slot) film[it - slot_.begin()] = f.film;
  }
}

}  // namespace drumlab
