// rcb_decompose_mpi (engine/parallel/mpi/rcb_mpi.hpp) against its oracle, rcb_decompose on every
// rank's particles gathered in rank order: the whole tree (boxes, axes, cuts, counts, weights)
// bit for bit and each particle's owner, by count and by weights that sum exactly (multiples of
// 1/4), on layouts that stress the histogram search: uniform points in unequal numbers per rank, a
// cluster a micrometre wide holding most of them (many rounds of narrowing), all points on one
// rank, fewer points than ranks, none at all. Points sharing coordinates (a lattice, and more equal
// coordinates than the gather takes) and a NaN and an infinite coordinate have no single serial
// answer: there the tree must be the same on every rank and every particle's owner that of
// rcb_owner, the owned counts adding up. Run
// under mpirun (ctest label mpi); prints one line per failed case and exits 1 if any failed.
#include <mpi.h>

#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "engine/parallel/mpi/rcb_mpi.hpp"

namespace {

using drumlab::Box;
using drumlab::Decomposition;
using drumlab::Vec3;

struct Points {
  std::vector<Vec3> x;
  std::vector<double> w;  // empty: by count
};

/// Every rank's points (and weights) on every rank, in rank order; `offset` is this rank's first.
Points gathered(drumlab::MpiComm& comm, const Points& mine, std::size_t& offset) {
  std::vector<double> flat;
  for (const Vec3& x : mine.x) flat.insert(flat.end(), {x[0], x[1], x[2]});
  const std::vector<double> all = comm.all_gather(std::span<const double>(flat));
  const std::vector<double> w = comm.all_gather(std::span<const double>(mine.w));
  const std::uint64_t n = mine.x.size();
  const std::vector<std::uint64_t> counts = comm.all_gather(std::span(&n, 1));
  offset = 0;
  for (int r = 0; r < comm.rank(); ++r) offset += counts[static_cast<std::size_t>(r)];
  Points out;
  for (std::size_t k = 0; k < all.size(); k += 3)
    out.x.emplace_back(all[k], all[k + 1], all[k + 2]);
  out.w = w;
  return out;
}

/// The tree as numbers, for comparing across ranks.
std::vector<double> flatten(const Decomposition& d) {
  std::vector<double> v;
  for (const auto& n : d.nodes) {
    v.insert(v.end(), {n.box.lo[0], n.box.lo[1], n.box.lo[2], n.box.hi[0], n.box.hi[1], n.box.hi[2],
                       double(n.rank_begin), double(n.rank_end), double(n.axis), n.cut,
                       double(n.left), double(n.right), double(n.count), n.weight});
  }
  for (std::size_t r = 0; r < d.boxes.size(); ++r) {
    v.insert(v.end(), {d.boxes[r].lo[0], d.boxes[r].lo[1], d.boxes[r].lo[2], d.boxes[r].hi[0],
                       d.boxes[r].hi[1], d.boxes[r].hi[2], double(d.owned[r]), d.owned_weight[r]});
  }
  return v;
}

/// "" when the distributed decomposition of `mine` passes; else what differed.
std::string check(drumlab::MpiComm& comm, const Points& mine, const Box& domain, bool exact) {
  const Decomposition d = drumlab::rcb_decompose_mpi(comm, mine.x, mine.w, domain);
  std::size_t offset = 0;
  const Points all = gathered(comm, mine, offset);
  std::string failed;
  const std::vector<double> tree = flatten(d);
  const std::vector<double> everywhere = comm.all_gather(std::span<const double>(tree));
  for (std::size_t k = 0; k < everywhere.size(); ++k) {
    if (everywhere[k] != tree[k % tree.size()]) failed = "the tree differs between ranks";
  }
  if (exact) {
    const Decomposition serial = drumlab::rcb_decompose(all.x, all.w, domain, comm.size());
    if (flatten(serial) != tree) failed = "the tree differs from rcb_decompose's";
    for (std::size_t i = 0; i < mine.x.size(); ++i) {
      if (d.owner[i] != serial.owner[offset + i]) failed = "an owner differs from rcb_decompose's";
    }
  }
  std::vector<std::size_t> owned(d.boxes.size(), 0);
  for (const Vec3& x : all.x) ++owned[static_cast<std::size_t>(drumlab::rcb_owner(d, x))];
  if (owned != d.owned) failed = "owned counts differ from rcb_owner's";
  for (std::size_t i = 0; i < mine.x.size(); ++i) {
    if (d.owner[i] != drumlab::rcb_owner(d, mine.x[i])) failed = "an owner differs from rcb_owner";
  }
  return failed;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int failed = 0;
  {
    drumlab::MpiComm comm(MPI_COMM_WORLD);
    const int rank = comm.rank();
    const Box deep = drumlab::drum_domain(0.2, 0.5);
    std::mt19937_64 rng(29 + static_cast<unsigned>(rank));
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> quarters(1, 12);
    const auto points = [&](std::size_t n, const std::function<Vec3()>& at, bool weighted) {
      Points p;
      for (std::size_t k = 0; k < n; ++k) {
        p.x.push_back(at());
        if (weighted) p.w.push_back(0.25 * quarters(rng));
      }
      return p;
    };
    const auto uniform = [&] {
      return Vec3(-0.1 + 0.2 * u(rng), -0.1 + 0.2 * u(rng), 0.5 * u(rng));
    };
    const auto clustered = [&] {  // 9 in 10 in a cube 1 micrometre wide
      if (u(rng) < 0.1) return uniform();
      return Vec3(0.01 + 1e-6 * u(rng), -0.02 + 1e-6 * u(rng), 0.3 + 1e-6 * u(rng));
    };
    const auto lattice = [&] {  // coordinates on 7 planes per axis
      const auto plane = [&](double lo, double hi) {
        return lo + (hi - lo) * std::floor(7.0 * u(rng)) / 7.0;
      };
      return Vec3(plane(-0.1, 0.1), plane(-0.1, 0.1), plane(0.0, 0.5));
    };
    const auto one_plane = [&] {  // 3 in 4 share z (more than the gather takes)
      Vec3 x = uniform();
      if (u(rng) < 0.75) x[2] = 0.25;
      return x;
    };
    const auto with_non_finite = [&](Points p) {  // as a run that blows up between checks
      if (rank == 1 % comm.size() && p.x.size() > 2) {
        p.x[0][2] = std::numeric_limits<double>::quiet_NaN();
        p.x[1][0] = std::numeric_limits<double>::infinity();
      }
      return p;
    };
    const std::size_t unequal = 3000 + 2000 * static_cast<std::size_t>(rank);
    struct Case {
      const char* name;
      Points mine;
      bool exact;
    };
    const std::vector<Case> cases = {
        {"uniform, unequal counts", points(unequal, uniform, false), true},
        {"uniform, weighted", points(unequal, uniform, true), true},
        {"clustered", points(20000, clustered, false), true},
        {"clustered, weighted", points(20000, clustered, true), true},
        {"all points on rank 0", points(rank == 0 ? 9000 : 0, uniform, false), true},
        {"all points on rank 0, weighted", points(rank == 0 ? 9000 : 0, uniform, true), true},
        {"fewer points than ranks", points(rank == 0 ? 2 : 0, uniform, false), true},
        {"no points", points(0, uniform, false), true},
        {"lattice (equal coordinates)", points(4000, lattice, false), false},
        {"lattice, weighted", points(4000, lattice, true), false},
        {"most points on one plane", points(5000, one_plane, false), false},
        {"a NaN and an infinite coordinate", with_non_finite(points(3000, uniform, true)), false},
    };
    for (const Case& c : cases) {
      const std::string what = check(comm, c.mine, deep, c.exact);
      int bad = what.empty() ? 0 : 1, any = 0;
      MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
      if (any == 0) continue;
      ++failed;
      if (rank == 0) {
        std::printf("rcb_check: %s: %s\n", c.name, bad ? what.c_str() : "(on another rank)");
      }
    }
    if (rank == 0 && failed == 0) std::printf("rcb_check: %zu cases passed\n", cases.size());
  }
  MPI_Finalize();
  return failed == 0 ? 0 : 1;
}
