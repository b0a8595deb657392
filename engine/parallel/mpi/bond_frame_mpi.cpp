#include "engine/parallel/mpi/bond_frame_mpi.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>

#include "engine/analysis/disjoint_sets.hpp"
#include "engine/contact/liquid_bridge.hpp"
#include "engine/parallel/mpi/global_order.hpp"
#include "engine/simulation.hpp"

namespace drumlab {

namespace {

/// The smallest stable id of each local particle's component (see the header); ghosts' labels as
/// their owners'.
void label_components(MpiDomain& domain, const Simulation& sim, const std::vector<Bond>& bonds,
                      const AgglomerateOptions& options, std::vector<std::uint64_t>& label) {
  const Particles& p = sim.particles();
  const std::size_t n = p.size();
  DisjointSets sets(n);
  for (const Bond& b : bonds) {
    if (bond_joins(b, options) && !(sim.is_ghost(b.i) && sim.is_ghost(b.j))) sets.unite(b.i, b.j);
  }
  std::vector<std::size_t> root(n);
  for (std::size_t i = 0; i < n; ++i) root[i] = sets.find(i);
  label.assign(p.id.begin(), p.id.end());
  std::vector<std::uint64_t> least(n), before(n);
  for (;;) {
    std::fill(least.begin(), least.end(), UINT64_MAX);
    for (std::size_t i = 0; i < n; ++i) least[root[i]] = std::min(least[root[i]], label[i]);
    for (std::size_t i = 0; i < n; ++i) label[i] = least[root[i]];
    before = label;
    domain.copy_to_ghosts(label);
    const bool changed = !std::equal(label.begin(), label.end(), before.begin());
    if (domain.comm().sum(std::uint64_t{changed}) == 0) return;
  }
}

/// A non-zero wall-bridge volume and where it comes in the serial run's sum.
struct WallValue {
  std::uint64_t part = 0, slot = 0;
  double volume = 0.0;
};

/// The wall bridges' liquid of all ranks, added in the serial order (see the header).
double ordered_wall_liquid(MpiComm& comm, const Simulation& sim,
                           const std::vector<std::uint64_t>& slot) {
  const Particles& p = sim.particles();
  std::vector<WallValue> mine;
  for (std::size_t w = 0; w < kWallBridgeVolumeArrays.size(); ++w) {
    const std::vector<double>* v = p.find_array(kWallBridgeVolumeArrays[w]);
    if (v == nullptr) continue;
    for (std::size_t i = 0; i < v->size(); ++i) {
      // Adding a zero changes no sum that is not -0, and this one starts at +0.
      if (!sim.is_ghost(i) && (*v)[i] != 0.0) mine.push_back({w, slot[i], (*v)[i]});
    }
  }
  const std::vector<std::vector<std::byte>> all = comm.gather(std::as_bytes(std::span(mine)));
  double sum = 0.0;
  if (comm.rank() == 0) {
    std::vector<WallValue> values;
    for (const std::vector<std::byte>& bytes : all) {
      const std::size_t at = values.size();
      values.resize(at + bytes.size() / sizeof(WallValue));
      if (bytes.empty()) continue;  // memcpy wants pointers even for 0 bytes (values may be empty)
      std::memcpy(static_cast<void*>(values.data() + at), bytes.data(), bytes.size());
    }
    std::sort(values.begin(), values.end(), [](const WallValue& a, const WallValue& b) {
      return a.part != b.part ? a.part < b.part : a.slot < b.slot;
    });
    for (const WallValue& v : values) sum += v.volume;
  }
  std::vector<std::byte> bytes(sizeof sum);
  std::memcpy(bytes.data(), &sum, sizeof sum);
  comm.broadcast(bytes);
  std::memcpy(&sum, bytes.data(), sizeof sum);
  return sum;
}

}  // namespace

MpiBondFrame mpi_bond_frame(MpiDomain& domain, const Simulation& sim,
                            const AgglomerateOptions& options) {
  if (options.community) {
    throw std::invalid_argument(
        "mpi_bond_frame: the community criterion needs the whole bond network (gather it)");
  }
  const Particles& p = sim.particles();
  const std::vector<std::uint64_t>& slot = domain.slots();
  std::vector<Bond> bonds;
  sim.bonds(bonds);
  MpiBondFrame f;
  std::vector<std::uint64_t> label;
  label_components(domain, sim, bonds, options, label);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!sim.is_ghost(i)) f.label.push_back(static_cast<std::uint32_t>(label[i]));
  }
  // This rank's bonds, keyed by their serial ends; their rows from the keys of all ranks.
  std::vector<OrderKey> keys;
  std::vector<const Bond*> mine;
  for (const Bond& b : bonds) {
    const bool i_first = slot[b.i] < slot[b.j];
    if (sim.is_ghost(i_first ? b.i : b.j)) continue;
    keys.push_back({std::min(slot[b.i], slot[b.j]), std::max(slot[b.i], slot[b.j])});
    mine.push_back(&b);
  }
  const std::vector<std::uint64_t> row = global_ranks(domain.comm(), keys);
  std::vector<std::size_t> order(mine.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return row[a] < row[b]; });
  for (const std::size_t k : order) {
    const Bond& b = *mine[k];
    const bool i_first = slot[b.i] < slot[b.j];
    f.bonds.push_back(p.id[i_first ? b.i : b.j], p.id[i_first ? b.j : b.i], b);
    f.row.push_back(row[k]);
  }
  f.total = domain.comm().sum(std::uint64_t{mine.size()});
  f.wall_liquid = ordered_wall_liquid(domain.comm(), sim, slot);
  return f;
}

}  // namespace drumlab
