#include "engine/parallel/mpi/global_order.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "engine/parallel/particle_pack.hpp"

namespace drumlab {

namespace {

constexpr std::size_t kSamplesPerRank = 64;

void put_key(std::vector<std::byte>& out, const OrderKey& k) {
  put_bytes(out, k.key);
  put_bytes(out, k.slot);
}

}  // namespace

std::vector<std::uint64_t> global_ranks(MpiComm& comm, std::span<const OrderKey> mine) {
  const auto ranks = static_cast<std::size_t>(comm.size());
  const std::size_t n = mine.size();
  std::vector<std::size_t> sorted(n);
  std::iota(sorted.begin(), sorted.end(), std::size_t{0});
  std::sort(sorted.begin(), sorted.end(),
            [&](std::size_t a, std::size_t b) { return mine[a] < mine[b]; });
  // Regular samples of the local order, gathered; ranks - 1 splitters from them.
  const std::size_t s = std::min(n, kSamplesPerRank);
  std::vector<std::uint64_t> flat;
  for (std::size_t k = 0; k < s; ++k) {
    const OrderKey& v = mine[sorted[k * n / s]];
    flat.push_back(v.key);
    flat.push_back(v.slot);
  }
  const std::vector<std::uint64_t> gathered = comm.all_gather(flat);
  std::vector<OrderKey> samples(gathered.size() / 2);
  for (std::size_t k = 0; k < samples.size(); ++k)
    samples[k] = {gathered[2 * k], gathered[2 * k + 1]};
  std::sort(samples.begin(), samples.end());
  std::vector<OrderKey> splitter;
  if (!samples.empty()) {
    for (std::size_t b = 1; b < ranks; ++b) splitter.push_back(samples[b * samples.size() / ranks]);
  }
  // Range b holds the keys above splitter b - 1 up to splitter b (the last: all above).
  const auto range_of = [&](std::size_t& b, const OrderKey& v) {
    while (b < splitter.size() && splitter[b] < v) ++b;
    return b;
  };
  std::vector<std::vector<std::byte>> out(ranks);
  for (std::size_t k = 0, b = 0; k < n; ++k)
    put_key(out[range_of(b, mine[sorted[k]])], mine[sorted[k]]);
  const std::vector<std::vector<std::byte>> in = comm.all_to_all(out);
  // This rank's range, sorted, numbered after the ranges of the ranks below.
  struct Held {
    OrderKey v;
    std::uint32_t from, at;  // source rank, position in its message
  };
  std::vector<Held> held;
  for (std::size_t q = 0; q < in.size(); ++q) {
    std::size_t pos = 0;
    for (std::uint32_t at = 0; pos < in[q].size(); ++at) {
      const auto key = get_bytes<std::uint64_t>(in[q], pos);
      const auto slot = get_bytes<std::uint64_t>(in[q], pos);
      held.push_back({{key, slot}, static_cast<std::uint32_t>(q), at});
    }
  }
  std::sort(held.begin(), held.end(), [](const Held& a, const Held& b) { return a.v < b.v; });
  const std::uint64_t count = held.size();
  const std::vector<std::uint64_t> counts = comm.all_gather(std::span(&count, 1));
  const std::uint64_t first =
      std::accumulate(counts.begin(), counts.begin() + comm.rank(), std::uint64_t{0});
  std::vector<std::vector<std::uint64_t>> numbered(ranks);
  for (std::size_t q = 0; q < ranks; ++q)
    numbered[q].resize(in[q].size() / (2 * sizeof(std::uint64_t)));
  for (std::size_t k = 0; k < held.size(); ++k) numbered[held[k].from][held[k].at] = first + k;
  std::vector<std::vector<std::byte>> reply(ranks);
  for (std::size_t q = 0; q < ranks; ++q) {
    reply[q].resize(numbered[q].size() * sizeof(std::uint64_t));
    if (!reply[q].empty()) std::memcpy(reply[q].data(), numbered[q].data(), reply[q].size());
  }
  const std::vector<std::vector<std::byte>> back = comm.all_to_all(reply);
  // The numbers come back in the order the keys were sent: the local order, range by range.
  std::vector<std::uint64_t> result(n);
  std::vector<std::size_t> pos(ranks, 0);
  for (std::size_t k = 0, b = 0; k < n; ++k) {
    const std::size_t q = range_of(b, mine[sorted[k]]);
    result[sorted[k]] = get_bytes<std::uint64_t>(back[q], pos[q]);
  }
  return result;
}

}  // namespace drumlab
