#include "engine/parallel/rcb.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

namespace drumlab {
namespace {

struct Splitter {
  std::span<const Vec3> position;
  std::span<const double> weight;  // empty: 1 each
  Decomposition* out;
  std::vector<Index> order;  // particle indices, each node's particles contiguous

  double weight_of(Index i) const { return weight.empty() ? 1.0 : weight[i]; }
  double sum(std::size_t begin, std::size_t end) const {
    if (weight.empty()) return static_cast<double>(end - begin);
    double s = 0.0;
    for (std::size_t k = begin; k < end; ++k) s += weight[order[k]];
    return s;
  }

  /// Places the `k` particles of [begin, end) with the smallest coordinate along `axis` first,
  /// choosing k so that their weight is nearest to `target`; returns k.
  std::size_t select(std::size_t begin, std::size_t end, int axis, double target) {
    auto less = [&](Index a, Index b) { return position[a][axis] < position[b][axis]; };
    const auto first = order.begin();
    const std::size_t m = end - begin;
    std::size_t k = 0;
    if (weight.empty()) {
      k = std::min<std::size_t>(m, static_cast<std::size_t>(std::llround(target)));
    } else {
      // Bisection over the rank of the split: [0, lo) are the lo smallest with weight acc <
      // target; the hi smallest weigh >= target (or hi = m).
      std::size_t lo = 0, hi = m;
      double acc = 0.0;
      while (hi - lo > 1) {
        const std::size_t mid = lo + (hi - lo) / 2;
        std::nth_element(first + static_cast<std::ptrdiff_t>(begin + lo),
                         first + static_cast<std::ptrdiff_t>(begin + mid),
                         first + static_cast<std::ptrdiff_t>(begin + hi), less);
        const double w = acc + sum(begin + lo, begin + mid);
        if (w < target) {
          acc = w;
          lo = mid;
        } else {
          hi = mid;
        }
      }
      // The split is lo or hi (they differ by the one particle at lo, when hi = lo + 1).
      const double w_lo = acc;
      const double w_hi = hi > lo ? acc + weight_of(order[begin + lo]) : acc;
      k = (std::abs(w_hi - target) < std::abs(w_lo - target)) ? hi : lo;
    }
    if (k > 0 && k < m) {
      std::nth_element(first + static_cast<std::ptrdiff_t>(begin),
                       first + static_cast<std::ptrdiff_t>(begin + k),
                       first + static_cast<std::ptrdiff_t>(end), less);
    }
    return k;
  }

  /// Splits node `id` (its particles are order[begin, end)) and its children.
  void split(int id, std::size_t begin, std::size_t end) {
    RcbNode node = out->nodes[static_cast<std::size_t>(id)];
    const int n = node.rank_end - node.rank_begin;
    if (n == 1) {
      const int rank = node.rank_begin;
      out->boxes[static_cast<std::size_t>(rank)] = node.box;
      out->owned[static_cast<std::size_t>(rank)] = end - begin;
      out->owned_weight[static_cast<std::size_t>(rank)] = node.weight;
      for (std::size_t k = begin; k < end; ++k) out->owner[order[k]] = rank;
      return;
    }
    const Vec3 extent = node.box.hi - node.box.lo;
    int axis = 0;
    extent.maxCoeff(&axis);
    const int n_left = n / 2;
    const double target = node.weight * n_left / n;
    const std::size_t k = select(begin, end, axis, target);
    // The cut: halfway between the two sides' nearest particles, inside the box.
    const double lo = node.box.lo[axis], hi = node.box.hi[axis];
    auto coord = [&](std::size_t at) { return position[order[at]][axis]; };
    double left_max = lo, right_min = hi;
    if (k > 0) {
      left_max = coord(begin);
      for (std::size_t a = begin + 1; a < begin + k; ++a) left_max = std::max(left_max, coord(a));
    }
    if (begin + k < end) right_min = coord(begin + k);
    double cut = (k == 0 && begin == end) ? 0.5 * (lo + hi) : 0.5 * (left_max + right_min);
    cut = std::clamp(cut, lo, hi);

    RcbNode left, right;
    left.box = right.box = node.box;
    left.box.hi[axis] = cut;
    right.box.lo[axis] = cut;
    left.rank_begin = node.rank_begin;
    left.rank_end = right.rank_begin = node.rank_begin + n_left;
    right.rank_end = node.rank_end;
    left.count = k;
    right.count = end - begin - k;
    left.weight = sum(begin, begin + k);
    right.weight = node.weight - left.weight;
    node.axis = axis;
    node.cut = cut;
    node.left = static_cast<int>(out->nodes.size());
    node.right = node.left + 1;
    out->nodes[static_cast<std::size_t>(id)] = node;
    out->nodes.push_back(left);
    out->nodes.push_back(right);
    split(node.left, begin, begin + k);
    split(node.right, begin + k, end);
  }
};

}  // namespace

Box drum_domain(double diameter, double depth) {
  const double r = 0.5 * diameter;
  return Box{Vec3(-r, -r, 0.0), Vec3(r, r, depth)};
}

Decomposition rcb_decompose(std::span<const Vec3> position, std::span<const double> weight,
                            const Box& domain, int ranks) {
  if (ranks < 1) throw InputError(fmt::format("ranks: must be >= 1, got {}", ranks));
  if (!weight.empty() && weight.size() != position.size()) {
    throw InputError(
        fmt::format("RCB weights: {} for {} particles", weight.size(), position.size()));
  }
  Decomposition d;
  const std::size_t n = position.size();
  const auto r = static_cast<std::size_t>(ranks);
  d.owner.assign(n, 0);
  d.boxes.assign(r, domain);
  d.owned.assign(r, 0);
  d.owned_weight.assign(r, 0.0);
  d.nodes.reserve(2 * r - 1);
  Splitter s{position, weight, &d, std::vector<Index>(n)};
  std::iota(s.order.begin(), s.order.end(), Index{0});
  RcbNode root;
  root.box = domain;
  root.rank_begin = 0;
  root.rank_end = ranks;
  root.count = n;
  root.weight = s.sum(0, n);
  d.nodes.push_back(root);
  s.split(0, 0, n);
  return d;
}

int rcb_owner(const Decomposition& d, const Vec3& x) {
  if (d.nodes.empty()) return 0;
  std::size_t id = 0;
  while (!d.nodes[id].leaf()) {
    const RcbNode& n = d.nodes[id];
    id = static_cast<std::size_t>(x[n.axis] < n.cut ? n.left : n.right);
  }
  return d.nodes[id].rank_begin;
}

}  // namespace drumlab
