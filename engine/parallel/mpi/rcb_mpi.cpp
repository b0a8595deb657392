#include "engine/parallel/mpi/rcb_mpi.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

namespace drumlab {
namespace {

constexpr std::size_t kBins = 128;         // histogram bins per box and round
constexpr std::uint64_t kGatherAt = 1024;  // candidates gathered once a bin holds no more
constexpr int kMaxRounds = 64;             // a bin of equal coordinates stops narrowing anyway

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The cut tree's shape (rank ranges and children), numbered depth first as rcb_decompose numbers
/// its nodes; boxes, axes and cuts come level by level.
void grow(std::vector<RcbNode>& nodes, std::size_t id) {
  const int begin = nodes[id].rank_begin, end = nodes[id].rank_end;
  if (end - begin == 1) return;
  RcbNode left, right;
  left.rank_begin = begin;
  left.rank_end = right.rank_begin = begin + (end - begin) / 2;
  right.rank_end = end;
  const auto l = nodes.size();
  nodes[id].left = static_cast<int>(l);
  nodes[id].right = static_cast<int>(l + 1);
  nodes.push_back(left);
  nodes.push_back(right);
  grow(nodes, l);
  grow(nodes, l + 1);
}

/// One box's search for its cut along `axis`: the candidates are its particles with coordinates
/// in [a, b); `below` of them (weighing `below_weight`) lie under a.
struct Search {
  std::size_t node = 0;
  int axis = 0;
  std::uint64_t m = 0;  ///< the box's particles, all ranks
  double target = 0.0;  ///< the weight the left side should carry
  std::uint64_t k = 0;  ///< by count: the left side's particle count
  double a = kInf, b = -kInf;
  std::uint64_t below = 0, inside = 0;
  double below_weight = 0.0;
  bool open = false;
};

/// Whole-tree quantities summed over the ranks.
struct Level {
  std::vector<std::uint64_t> count;
  std::vector<double> weight;
  std::vector<double> extremes;  ///< per box: smallest coordinate, then minus the largest
};

class DistributedRcb {
 public:
  DistributedRcb(MpiComm& comm, std::span<const Vec3> position, std::span<const double> weight,
                 bool weighted)
      : comm_(comm), position_(position), weight_(weight), weighted_(weighted) {}

  Decomposition run(const Box& domain) {
    const auto r = static_cast<std::size_t>(comm_.size());
    d_.owner.assign(position_.size(), 0);
    d_.boxes.assign(r, domain);
    d_.owned.assign(r, 0);
    d_.owned_weight.assign(r, 0.0);
    d_.nodes.reserve(2 * r - 1);
    RcbNode root;
    root.box = domain;
    root.rank_end = comm_.size();
    d_.nodes.push_back(root);
    grow(d_.nodes, 0);
    members_.resize(d_.nodes.size());
    members_[0].resize(position_.size());
    std::iota(members_[0].begin(), members_[0].end(), Index{0});
    std::vector<std::size_t> level = {0};
    while (!level.empty()) level = cut_level(level);
    return std::move(d_);
  }

 private:
  double weight_of(Index i) const { return weight_.empty() ? 1.0 : weight_[i]; }
  double coord(Index i, int axis) const { return position_[i][axis]; }
  static int longest_axis(const Box& box) {
    int axis = 0;
    (box.hi - box.lo).maxCoeff(&axis);
    return axis;
  }

  /// Cuts the inner boxes of `level` (node ids), records its leaves; returns the next level.
  std::vector<std::size_t> cut_level(const std::vector<std::size_t>& level) {
    const Level sums = measure(level);
    std::vector<Search> searches;
    for (std::size_t l = 0; l < level.size(); ++l) {
      RcbNode& node = d_.nodes[level[l]];
      node.count = static_cast<std::size_t>(sums.count[l]);
      node.weight = weighted_ ? sums.weight[l] : static_cast<double>(sums.count[l]);
      if (node.rank_end - node.rank_begin == 1) {
        const auto rank = static_cast<std::size_t>(node.rank_begin);
        d_.boxes[rank] = node.box;
        d_.owned[rank] = node.count;
        d_.owned_weight[rank] = node.weight;
        for (const Index i : members_[level[l]]) d_.owner[i] = node.rank_begin;
        continue;
      }
      Search s;
      s.node = level[l];
      s.axis = longest_axis(node.box);
      s.m = sums.count[l];
      const int n = node.rank_end - node.rank_begin;
      s.target = node.weight * (n / 2) / n;  // rcb_decompose's expression, bit for bit
      if (!weighted_) s.k = std::min<std::uint64_t>(s.m, std::llround(s.target));
      if (s.m > 0) {
        s.a = sums.extremes[2 * l];
        s.b = std::nextafter(-sums.extremes[2 * l + 1], kInf);
        s.inside = s.m;
        s.open = s.m > kGatherAt && s.a < s.b;  // not when no coordinate is finite
      }
      searches.push_back(s);
    }
    for (int round = 0; round < kMaxRounds; ++round) {
      if (!narrow(searches)) break;
    }
    decide(searches);
    std::vector<std::size_t> next;
    for (const Search& s : searches) {
      const RcbNode& node = d_.nodes[s.node];
      next.push_back(static_cast<std::size_t>(node.left));
      next.push_back(static_cast<std::size_t>(node.right));
    }
    return next;
  }

  /// Count, weight and coordinate range of every box of `level` (along its cut axis; none for a
  /// leaf), summed over the ranks.
  Level measure(const std::vector<std::size_t>& level) {
    Level s{std::vector<std::uint64_t>(level.size(), 0), std::vector<double>(level.size(), 0.0),
            std::vector<double>(2 * level.size(), kInf)};
    for (std::size_t l = 0; l < level.size(); ++l) {
      const RcbNode& node = d_.nodes[level[l]];
      const std::vector<Index>& mine = members_[level[l]];
      s.count[l] = mine.size();
      for (const Index i : mine) s.weight[l] += weight_of(i);
      if (node.rank_end - node.rank_begin == 1) continue;
      const int axis = longest_axis(node.box);
      for (const Index i : mine) {
        const double x = coord(i, axis);
        if (!std::isfinite(x)) continue;  // counted, never a candidate (see decide)
        s.extremes[2 * l] = std::min(s.extremes[2 * l], x);
        s.extremes[2 * l + 1] = std::min(s.extremes[2 * l + 1], -x);
      }
    }
    comm_.sum(std::span(s.count));
    if (weighted_) comm_.agreed_sum(std::span(s.weight));
    comm_.min(std::span(s.extremes));
    return s;
  }

  /// One round of histograms over the open searches' intervals: each narrows to the bin that
  /// holds the particle deciding its split. Returns false when none was open.
  bool narrow(std::vector<Search>& searches) {
    std::vector<Search*> open;
    for (Search& s : searches) {
      if (s.open) open.push_back(&s);
    }
    if (open.empty()) return false;
    std::vector<std::uint64_t> count(open.size() * kBins, 0);
    std::vector<double> weight(open.size() * kBins, 0.0);
    std::vector<double> edges(open.size() * (kBins + 1));
    for (std::size_t o = 0; o < open.size(); ++o) {
      const Search& s = *open[o];
      double* e = edges.data() + o * (kBins + 1);
      e[0] = s.a;
      e[kBins] = s.b;
      for (std::size_t j = 1; j < kBins; ++j) {
        e[j] = s.a + (s.b - s.a) * static_cast<double>(j) / static_cast<double>(kBins);
      }
      for (const Index i : members_[s.node]) {
        const double x = coord(i, s.axis);
        if (!(x >= s.a && x < s.b)) continue;
        const auto bin = static_cast<std::size_t>(std::upper_bound(e + 1, e + kBins, x) - (e + 1));
        ++count[o * kBins + bin];
        weight[o * kBins + bin] += weight_of(i);
      }
    }
    comm_.sum(std::span(count));
    if (weighted_) comm_.agreed_sum(std::span(weight));
    for (std::size_t o = 0; o < open.size(); ++o) {
      Search& s = *open[o];
      const std::uint64_t* c = count.data() + o * kBins;
      const double* w = weight.data() + o * kBins;
      const double* e = edges.data() + o * (kBins + 1);
      // The bin of the deciding particle: by count the k-th (the first for k = 0); by weight the
      // first whose prefix weight reaches the target (the last particle if none does).
      const std::uint64_t p = std::max<std::uint64_t>(s.k, 1);
      std::size_t last = kBins;
      std::size_t j = kBins;
      std::uint64_t acc = s.below;
      double acc_w = s.below_weight;
      for (std::size_t t = 0; t < kBins; ++t) {
        if (c[t] == 0) continue;
        last = t;
        if (weighted_ ? acc_w + w[t] >= s.target : acc + c[t] >= p) {
          j = t;
          break;
        }
        acc += c[t];
        acc_w += w[t];
      }
      if (j == kBins) {  // not reached (rounding): the last non-empty bin
        if (last == kBins) {
          s.open = false;  // nothing inside: cannot happen with consistent sums
          continue;
        }
        j = last;
        acc = s.below;
        acc_w = s.below_weight;
        for (std::size_t t = 0; t < j; ++t) acc += c[t], acc_w += w[t];
      }
      const bool narrower = e[j] > s.a || e[j + 1] < s.b;
      s.below = acc;
      s.below_weight = acc_w;
      s.a = e[j];
      s.b = e[j + 1];
      s.inside = c[j];
      s.open = narrower && s.inside > kGatherAt;
    }
    return true;
  }

  /// Gathers every search's candidates, chooses each split as rcb_decompose does and cuts.
  void decide(std::vector<Search>& searches) {
    // This rank's candidates per search (a count, then coordinate and weight pairs), and the
    // largest coordinate under each interval and the smallest above it.
    std::vector<double> mine, outside(2 * searches.size(), -kInf);
    for (std::size_t n = 0; n < searches.size(); ++n) {
      const Search& s = searches[n];
      const std::size_t at = mine.size();
      mine.push_back(0.0);
      for (const Index i : members_[s.node]) {
        const double x = coord(i, s.axis);
        if (!std::isfinite(x)) continue;
        if (x < s.a) {
          outside[2 * n] = std::max(outside[2 * n], x);
        } else if (x >= s.b) {
          outside[2 * n + 1] = std::max(outside[2 * n + 1], -x);
        } else {
          mine.insert(mine.end(), {x, weight_of(i)});
          mine[at] += 1.0;
        }
      }
    }
    const std::vector<double> all = comm_.all_gather(std::span<const double>(mine));
    if (!searches.empty()) comm_.max(std::span(outside));
    std::vector<std::vector<std::pair<double, double>>> candidates(searches.size());
    for (std::size_t pos = 0; pos < all.size();) {  // each rank's part, searches in order
      for (auto& c : candidates) {
        const auto count = static_cast<std::size_t>(all[pos++]);
        for (std::size_t t = 0; t < count; ++t, pos += 2) c.emplace_back(all[pos], all[pos + 1]);
      }
    }
    for (std::size_t n = 0; n < searches.size(); ++n) {
      std::sort(candidates[n].begin(), candidates[n].end());
      cut(searches[n], candidates[n], outside[2 * n], -outside[2 * n + 1]);
    }
  }

  /// The split of search s from its sorted candidates and the nearest coordinates outside them;
  /// sets the node's cut and its children's boxes and particles.
  void cut(const Search& s, const std::vector<std::pair<double, double>>& cand, double max_below,
           double min_above) {
    RcbNode& node = d_.nodes[s.node];
    const std::uint64_t q = cand.size();
    std::uint64_t k = s.k;
    if (weighted_ && s.m > 0 && q > 0) {
      // rcb_decompose's rule: j, the first particle whose prefix weight reaches the target (or
      // the last), and k = j or j - 1, whichever prefix is nearer the target.
      std::uint64_t t = 1;
      double before = s.below_weight, through = before + cand[0].second;
      while (t < q && !(through >= s.target)) {
        before = through;
        through += cand[t++].second;
      }
      const std::uint64_t j = s.below + t;
      k = std::abs(through - s.target) < std::abs(before - s.target) ? j : j - 1;
    }
    // The j-th smallest coordinate (1-based), among the candidates or next to them.
    auto value = [&](std::uint64_t j) {
      if (j <= s.below) return max_below;
      if (j - s.below <= q) return cand[j - s.below - 1].first;
      return min_above;
    };
    const double lo = node.box.lo[s.axis], hi = node.box.hi[s.axis];
    const double left_max = k == 0 ? lo : value(k);
    const double right_min = k >= s.m ? hi : value(k + 1);
    double cut = s.m == 0 ? 0.5 * (lo + hi) : 0.5 * (left_max + right_min);
    if (!std::isfinite(cut)) cut = 0.5 * (lo + hi);  // a box of non-finite positions only
    node.axis = s.axis;
    node.cut = std::clamp(cut, lo, hi);
    RcbNode& left = d_.nodes[static_cast<std::size_t>(node.left)];
    RcbNode& right = d_.nodes[static_cast<std::size_t>(node.right)];
    left.box = right.box = node.box;
    left.box.hi[s.axis] = node.cut;
    right.box.lo[s.axis] = node.cut;
    std::vector<Index>& to_left = members_[static_cast<std::size_t>(node.left)];
    std::vector<Index>& to_right = members_[static_cast<std::size_t>(node.right)];
    for (const Index i : members_[s.node]) {
      (coord(i, s.axis) < node.cut ? to_left : to_right).push_back(i);
    }
    members_[s.node] = {};
  }

  MpiComm& comm_;
  std::span<const Vec3> position_;
  std::span<const double> weight_;
  bool weighted_;
  Decomposition d_;
  std::vector<std::vector<Index>> members_;  ///< this rank's particles in each node
};

}  // namespace

Decomposition rcb_decompose_mpi(MpiComm& comm, std::span<const Vec3> position,
                                std::span<const double> weight, const Box& domain) {
  const bool weighted = comm.max(weight.empty() ? 0.0 : 1.0) > 0.0;
  if (weighted && weight.size() != position.size()) {
    throw std::invalid_argument("RCB: weights on some ranks, not for every particle on this one");
  }
  return DistributedRcb(comm, position, weight, weighted).run(domain);
}

}  // namespace drumlab
