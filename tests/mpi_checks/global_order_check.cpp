// global_ranks (engine/parallel/mpi/global_order.hpp) against its oracle, every rank's keys
// gathered and sorted on every rank, on layouts that stress the splitters: random keys in unequal
// numbers per rank, a rank without keys, all keys on one rank, one Morton key shared by every
// particle (the slots decide), fewer keys than ranks, and none at all. Run under mpirun (ctest
// label mpi); prints one line per failed case and exits 1 if any failed.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "engine/parallel/mpi/global_order.hpp"

namespace {

using drumlab::OrderKey;

/// The oracle: every key on every rank, sorted; each of mine's index there.
std::vector<std::uint64_t> gathered_ranks(drumlab::MpiComm& comm,
                                          const std::vector<OrderKey>& mine) {
  std::vector<std::uint64_t> flat;
  for (const OrderKey& k : mine) flat.insert(flat.end(), {k.key, k.slot});
  const std::vector<std::uint64_t> all_flat = comm.all_gather(flat);
  std::vector<OrderKey> all(all_flat.size() / 2);
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = {all_flat[2 * k], all_flat[2 * k + 1]};
  std::sort(all.begin(), all.end());
  std::vector<std::uint64_t> out;
  for (const OrderKey& k : mine) {
    out.push_back(
        static_cast<std::uint64_t>(std::lower_bound(all.begin(), all.end(), k) - all.begin()));
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int failed = 0;
  {
    drumlab::MpiComm comm(MPI_COMM_WORLD);
    const int rank = comm.rank(), size = comm.size();
    // Slots are unique over ranks: slot = rank + size * k.
    const auto keys = [&](std::size_t n, const std::function<std::uint64_t(std::size_t)>& key) {
      std::vector<OrderKey> v;
      for (std::size_t k = 0; k < n; ++k) {
        v.push_back(
            {key(k), static_cast<std::uint64_t>(rank) + static_cast<std::uint64_t>(size) * k});
      }
      return v;
    };
    std::mt19937_64 rng(17 + static_cast<unsigned>(rank));
    std::uniform_int_distribution<std::uint64_t> u(0, 5000);
    const std::vector<std::pair<const char*, std::vector<OrderKey>>> cases = {
        {"random keys, unequal counts",
         keys(300 + 1000 * static_cast<std::size_t>(rank), [&](std::size_t) { return u(rng); })},
        {"rank 1 without keys", keys(rank == 1 ? 0 : 700, [&](std::size_t) { return u(rng); })},
        {"all keys on rank 0", keys(rank == 0 ? 2000 : 0, [&](std::size_t) { return u(rng); })},
        {"one Morton key for all", keys(500, [](std::size_t) { return std::uint64_t{42}; })},
        {"keys descending with the slots", keys(900, [](std::size_t k) { return 100000 - k; })},
        {"fewer keys than ranks",
         keys(rank == 0 ? 1 : 0, [](std::size_t) { return std::uint64_t{7}; })},
        {"no keys", {}},
    };
    for (const auto& [name, mine] : cases) {
      const std::vector<std::uint64_t> got = drumlab::global_ranks(comm, mine);
      const std::vector<std::uint64_t> want = gathered_ranks(comm, mine);
      const int bad = got != want ? 1 : 0;
      int any = 0;
      MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
      if (any != 0) {
        if (rank == 0) std::printf("global_ranks differs from the gathered order: %s\n", name);
        failed = 1;
      }
    }
    if (rank == 0 && failed == 0)
      std::printf("global_ranks: %zu cases on %d ranks equal the gathered order\n", cases.size(),
                  size);
  }
  MPI_Finalize();
  return failed;
}
