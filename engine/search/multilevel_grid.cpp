#include "engine/search/multilevel_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <type_traits>

#include <fmt/format.h>

#include "engine/counting_sort.hpp"
#include "engine/parallel_copy.hpp"
#include "engine/search/grid_axes.hpp"
#include "engine/search/search_input.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/threads.hpp"

namespace drumlab {

namespace {

constexpr double kDenseCellsPerParticle = 64.0;
constexpr double kDenseCellFloor = 1048576.0;  // 2^20

/// Up to kMaxExactLevels distinct values, or the news that there are more.
struct DistinctRadii {
  std::array<double, kMaxExactLevels> value{};
  std::size_t size = 0;
  bool overflow = false;
  void add(double r) {
    if (overflow) return;
    for (std::size_t k = 0; k < size; ++k) {
      if (value[k] == r) return;
    }
    if (size == kMaxExactLevels) {
      overflow = true;
      return;
    }
    value[size++] = r;
  }
  void merge(const DistinctRadii& o) {
    overflow = overflow || o.overflow;
    for (std::size_t k = 0; k < o.size; ++k) add(o.value[k]);
  }
};
#pragma omp declare reduction(distinct_radii:DistinctRadii : omp_out.merge(omp_in))

}  // namespace

std::string_view MultiLevelGridSearch::description() const {
  return search_method(name()).description;
}

void MultiLevelGridSearch::find_pairs(const SearchInput& in, std::vector<IndexPair>& out) {
  const auto t0 = SearchClock::now();
  validate_search_input(in);
  const std::size_t n = in.position.size();
  reset_counters(n);
  out.clear();
  timings_ = {};
  if (n == 0) return;
  margin_ = in.margin;
  period_ = in.period_z.value_or(0.0);
  assign_levels(in);
  const Box bounds = search_bounds(in);
  std::uint64_t cells_total = 0;
  for (Level& level : levels_) {
    lay_level(level, in, bounds);
    cells_total += static_cast<std::uint64_t>(level.n[0] * level.n[1] * level.n[2]);
  }
  timings_.build = seconds_since(t0);
  const auto t1 = SearchClock::now();
  for (const Level& level : levels_) {
    if (level.hashed) {
      visit_level(level, level.hashed_index, in, out);
    } else {
      visit_level(level, level.dense, in, out);
    }
  }
  timings_.visit = seconds_since(t1);
  counters_.cells_total = cells_total;
  counters_.pairs_found = out.size();
}

void MultiLevelGridSearch::assign_levels(const SearchInput& in) {
  const std::size_t n = in.position.size();
  const auto count = static_cast<std::int64_t>(n);
  // The distinct radii, by a scan that gives up after kMaxExactLevels of them: beds have a few
  // size classes, and sorting every radius cost more than the rest of the level assignment. Each
  // thread scans its share; the set (sorted below) does not depend on the team.
  DistinctRadii found;
  double rmin = in.radius[0];
#pragma omp parallel for schedule(static) if (count >= kParallelMinElements) \
    reduction(distinct_radii                                                 \
              : found) reduction(min                                         \
                                 : rmin)
  for (std::int64_t i = 0; i < count; ++i) {
    const double r = in.radius[static_cast<std::size_t>(i)];
    found.add(r);
    rmin = std::min(rmin, r);
  }
  const bool exact = !found.overflow;
  distinct_.assign(found.value.begin(), found.value.begin() + found.size);
  std::sort(distinct_.begin(), distinct_.end());
  std::vector<int>& raw = raw_;
  raw.resize(n);
  int top = 0;
#pragma omp parallel for schedule(static) if (count >= kParallelMinElements) reduction(max : top)
  for (std::int64_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const double r = in.radius[i];
    raw[i] = exact ? static_cast<int>(std::lower_bound(distinct_.begin(), distinct_.end(), r) -
                                      distinct_.begin())
                   : std::min(200, static_cast<int>(std::floor(std::log2(r / rmin))));
    top = std::max(top, raw[i]);
  }
  // Keep only occupied levels, smallest first.
  std::vector<int>& compact = compact_;
  compact.assign(static_cast<std::size_t>(top) + 1, -1);
  for (int l : raw) compact[l] = 0;
  int next = 0;
  for (int& c : compact) {
    if (c == 0) c = next++;
  }
  levels_.resize(static_cast<std::size_t>(next));
  // Each level's members in particle order: a stable counting sort by level, then copies.
  const auto level_of = [&](std::size_t i) {
    return static_cast<std::size_t>(compact[static_cast<std::size_t>(raw[i])]);
  };
  std::vector<Index>& by_level = level_members_;
  by_level.resize(n);
  constexpr std::size_t kParticlesPerShare = 32768;  // below this, one thread
  const std::size_t t_count = counting_sort_by_row(
      n, levels_.size(), kParticlesPerShare, level_fill_, level_of,
      [&](std::size_t i, std::uint32_t slot) { by_level[slot] = static_cast<Index>(i); });
  std::uint32_t begin = 0;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    Level& level = levels_[l];
    const std::uint32_t end = level_fill_[l * t_count + t_count - 1];
    parallel_assign<Index>(level.order,
                           std::span<const Index>(by_level).subspan(begin, end - begin));
    double rmax = 0.0;
    const auto members = static_cast<std::int64_t>(end - begin);
#pragma omp parallel for schedule(static) if (members >= kParallelMinElements) reduction(max : rmax)
    for (std::int64_t k = 0; k < members; ++k) {
      rmax = std::max(rmax, in.radius[level.order[static_cast<std::size_t>(k)]]);
    }
    level.rmax = rmax;
    begin = end;
  }
}

void MultiLevelGridSearch::lay_level(Level& level, const SearchInput& in, const Box& bounds) {
  const double reach = 2.0 * level.rmax + in.margin + kTouchTolerance;
  // Cells a hair wider than the reach, so that the round-off allowance of reach_cells() does not
  // push the stencil from 1 to 2 cells each way (5^3 instead of 3^3 cells visited).
  const GridAxes axes(bounds, reach * (1.0 + 1e-9), "mlgrid");
  size_level(level, axes, reach, bounds, in);
  bin_members(level, axes, in);
  sort_members(level);
  gather_members(level, in);
  if (level.hashed) index_hashed_cells(level);  // else the counting sort filled the dense ranges
}

// The level's cells (along a periodic z, layers that tile the period), its stencil, and whether
// its cell index is dense or hashed.
void MultiLevelGridSearch::size_level(Level& level, const GridAxes& axes, double reach,
                                      const Box& bounds, const SearchInput& in) {
  level.origin = bounds.lo;
  level.b = axes.side();
  level.k = axes.reach_cells(reach);
  level.n[0] = axes.cells(0);
  level.n[1] = axes.cells(1);
  level.periodic = in.period_z.has_value();
  slack_ = std::max(slack_, axes.slack());
  if (level.periodic) {
    // Layers must tile the period; fewer than 2k+1 would make the stencil visit one twice.
    level.n[2] = static_cast<std::int64_t>(*in.period_z / level.b);
    if (level.n[2] < 2 * level.k + 1) level.n[2] = 1;
    level.bz = *in.period_z / static_cast<double>(level.n[2]);
  } else {
    level.n[2] = axes.cells(2);
    level.bz = level.b;
  }
  const bool three_d = level.n[2] > 1;
  if (level.stencil.kmax() != level.k || level.stencil.rows.empty() ||
      (level.stencil.offsets.size() > 0 && (level.stencil.offsets.back().dz != 0) != three_d)) {
    level.stencil = HalfStencil(level.k, three_d);
  }
  const double m = static_cast<double>(level.order.size());
  const double total = static_cast<double>(level.n[0]) * static_cast<double>(level.n[1]) *
                       static_cast<double>(level.n[2]);
  level.hashed = total > kDenseCellsPerParticle * m + kDenseCellFloor;
}

// The cell of each member, by slot (scratch_cell).
void MultiLevelGridSearch::bin_members(Level& level, const GridAxes& axes, const SearchInput& in) {
  const bool three_d = level.n[2] > 1;
  std::vector<CellCoord>& cell_of = level.scratch_cell;
  cell_of.resize(level.order.size());
  const auto count = static_cast<std::int64_t>(level.order.size());
#pragma omp parallel for schedule(static) if (count >= kParallelMinElements)
  for (std::int64_t ss = 0; ss < count; ++ss) {
    const auto s = static_cast<std::size_t>(ss);
    const Vec3& x = in.position[level.order[s]];
    CellCoord c{axes.coord(x.x(), 0), axes.coord(x.y(), 1), 0};
    if (three_d) {
      c.z = level.periodic
                ? std::min<std::int64_t>(static_cast<std::int64_t>(std::floor(x.z() / level.bz)),
                                         level.n[2] - 1)
                : axes.coord(x.z(), 2);
    }
    cell_of[s] = c;
  }
}

// The members' order sorted by cell (scratch_perm): a sort for a hashed index, else a counting
// sort that also fills the dense cell ranges.
void MultiLevelGridSearch::sort_members(Level& level) {
  const std::vector<CellCoord>& cell_of = level.scratch_cell;
  std::vector<std::size_t>& perm = level.scratch_perm;
  perm.resize(level.order.size());
  if (level.hashed) {
    std::iota(perm.begin(), perm.end(), std::size_t{0});
    std::sort(perm.begin(), perm.end(), [&](std::size_t a, std::size_t b) {
      const CellCoord& ca = cell_of[a];
      const CellCoord& cb = cell_of[b];
      if (ca.z != cb.z) return ca.z < cb.z;
      if (ca.y != cb.y) return ca.y < cb.y;
      if (ca.x != cb.x) return ca.x < cb.x;
      return a < b;
    });
  } else {  // counting sort by cell: O(members + cells), stable
    level.dense.reset(level.n[0], level.n[1], level.n[2]);
    for (const CellCoord& c : cell_of) ++level.dense.at(level.dense.linear(c)).end;
    std::uint32_t running = 0;
    const std::int64_t cells = level.n[0] * level.n[1] * level.n[2];
    for (std::int64_t c = 0; c < cells; ++c) {
      CellRange& r = level.dense.at(c);
      const std::uint32_t size = r.end;
      r = CellRange{running, running, running};
      running += size;
    }
    for (std::size_t s = 0; s < cell_of.size(); ++s) {
      perm[level.dense.at(level.dense.linear(cell_of[s])).end++] = s;
    }
  }
}

// The members, their cells, positions and radii in cell-sorted order.
void MultiLevelGridSearch::gather_members(Level& level, const SearchInput& in) {
  const std::vector<CellCoord>& cell_of = level.scratch_cell;
  const std::vector<std::size_t>& perm = level.scratch_perm;
  std::vector<Index>& members = level.scratch_order;
  parallel_assign<Index>(members, level.order);
  const std::size_t count = members.size();
  level.position.resize(count);
  level.radius.resize(count);
  level.cell.resize(count);
  const auto slots = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (slots >= kParallelMinElements)
  for (std::int64_t ss = 0; ss < slots; ++ss) {
    const auto s = static_cast<std::size_t>(ss);
    level.order[s] = members[perm[s]];
    level.cell[s] = cell_of[perm[s]];
    level.position[s] = in.position[level.order[s]];
    level.radius[s] = in.radius[level.order[s]];
  }
}

// The hashed index of the occupied cells (the slots are sorted by cell).
void MultiLevelGridSearch::index_hashed_cells(Level& level) {
  const std::size_t count = level.order.size();
  std::size_t occupied = 0;
  for (std::size_t s = 0; s < count; ++s) {
    occupied += (s == 0 || !(level.cell[s] == level.cell[s - 1]));
  }
  level.hashed_index.reset(occupied);
  for (std::size_t s = 0; s < count;) {
    std::size_t e = s + 1;
    while (e < count && level.cell[e] == level.cell[s]) ++e;
    const CellRange r{static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(e),
                      static_cast<std::uint32_t>(e)};
    level.hashed_index.insert(level.cell[s], r);
    s = e;
  }
}

bool MultiLevelGridSearch::wrap(const Level& level, CellCoord& c) const {
  if (c.x < 0 || c.x >= level.n[0] || c.y < 0 || c.y >= level.n[1]) return false;
  if (level.periodic && level.n[2] > 1) {
    if (c.z < 0) {
      c.z += level.n[2];
    } else if (c.z >= level.n[2]) {
      c.z -= level.n[2];
    }
    return true;
  }
  return c.z >= 0 && c.z < level.n[2];
}

template <class Cells>
void MultiLevelGridSearch::visit_level(const Level& level, const Cells& cells,
                                       const SearchInput& in, std::vector<IndexPair>& out) {
  const double period = in.period_z.value_or(0.0);
  const double margin = in.margin + kTouchTolerance;
  const std::size_t l = static_cast<std::size_t>(&level - levels_.data());
  std::uint64_t cells_visited = 0, pairs_tested = 0;
  // Each thread takes a contiguous block of slots and collects its pairs; the blocks are joined
  // in order, so the output does not depend on the thread count. Counters per particle are
  // written by the one thread that owns the particle.
  const int threads = slices_.prepare(max_threads());
  const auto slots = static_cast<std::int64_t>(level.order.size());
#pragma omp parallel num_threads(threads) reduction(+ : cells_visited, pairs_tested)
  {
    std::vector<IndexPair>& mine = slices_.slice(thread_number());
#pragma omp for schedule(static)
    for (std::int64_t ss = 0; ss < slots; ++ss) {
      const auto s = static_cast<std::size_t>(ss);
      const Vec3& xi = level.position[s];
      const double ri = level.radius[s];
      const Index pi = level.order[s];
      const CellCoord ci = level.cell[s];
      const SortedParticles sp = level.sorted();
      std::uint32_t my_cells = 1, my_tests = 0;
      CellRange r;
      cells.find(ci, r);
      my_tests += scan_slots(sp, xi, ri, pi, static_cast<std::uint32_t>(s) + 1, r.end, margin,
                             period, mine);
      if constexpr (std::is_same_v<Cells, DenseCellIndex>) {
        for (const StencilRow& row : level.stencil.rows[level.k]) {
          CellCoord c{0, ci.y + row.dy, ci.z + row.dz};
          if (!wrap(level, c)) continue;
          const std::int64_t x0 = std::max<std::int64_t>(ci.x + row.dx_lo, 0);
          const std::int64_t x1 = std::min<std::int64_t>(ci.x + row.dx_hi, level.n[0] - 1);
          if (x0 > x1) continue;
          my_cells += static_cast<std::uint32_t>(x1 - x0 + 1);
          c.x = x0;
          const std::uint32_t begin = cells.cell(c).begin;
          c.x = x1;
          my_tests += scan_slots(sp, xi, ri, pi, begin, cells.cell(c).end, margin, period, mine);
        }
      } else {
        const auto& offsets = level.stencil.offsets;
        for (std::uint32_t o = 0; o < level.stencil.prefix_end[level.k]; ++o) {
          CellCoord c{ci.x + offsets[o].dx, ci.y + offsets[o].dy, ci.z + offsets[o].dz};
          if (!wrap(level, c)) continue;
          ++my_cells;
          if (cells.find(c, r)) {
            my_tests += scan_slots(sp, xi, ri, pi, r.begin, r.end, margin, period, mine);
          }
        }
      }
      cells_per_particle_[pi] = my_cells;
      tests_per_particle_[pi] = my_tests;
      for (std::size_t h = 0; h < l; ++h) {
        const Level& small = levels_[h];
        if (small.hashed) {
          visit_cross(level, s, small, small.hashed_index, in, mine);
        } else {
          visit_cross(level, s, small, small.dense, in, mine);
        }
      }
      cells_visited += cells_per_particle_[pi];
      pairs_tested += tests_per_particle_[pi];
    }
  }
  slices_.join(out);
  counters_.cells_visited += cells_visited;
  counters_.pairs_tested += pairs_tested;
}

template <class Row>
void MultiLevelGridSearch::cross_rows(const Level& small, const Vec3& xi, double ri, double margin,
                                      Row&& row) const {
  // Every partner in the smaller level lies within `half` of x_i (widened against round-off).
  const double half = (ri + small.rmax + margin) * (1.0 + 1e-9);
  // x_i in cell units of the smaller level, and the cell range of the box [x - half, x + half].
  double u[3];
  std::int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double side = a == 2 ? small.bz : small.b;
    const double origin = (a == 2 && small.periodic) ? 0.0 : small.origin[a];
    u[a] = (xi[a] - origin) / side;
    lo[a] = static_cast<std::int64_t>(std::floor(u[a] - half / side - slack_));
    hi[a] = static_cast<std::int64_t>(std::floor(u[a] + half / side + slack_));
  }
  const bool wrap_z = small.periodic && small.n[2] > 1 && hi[2] - lo[2] + 1 < small.n[2];
  // Periodic, and the box spans the whole period: every layer once (clamping the range instead
  // would drop the layers that wrap). The layers' distances along z then cannot prune.
  const bool whole_period = small.periodic && !wrap_z;
  if (whole_period) {
    lo[2] = 0;
    hi[2] = small.n[2] - 1;
  } else if (!wrap_z) {
    lo[2] = std::max<std::int64_t>(lo[2], 0);
    hi[2] = std::min<std::int64_t>(hi[2], small.n[2] - 1);
  }
  lo[0] = std::max<std::int64_t>(lo[0], 0);
  hi[0] = std::min<std::int64_t>(hi[0], small.n[0] - 1);
  lo[1] = std::max<std::int64_t>(lo[1], 0);
  hi[1] = std::min<std::int64_t>(hi[1], small.n[1] - 1);
  if (lo[0] > hi[0] || lo[1] > hi[1]) return;
  // Gap from x_i to the slab of cells [c, c + 1) along one axis, in cells, less the round-off
  // slack: a row of cells whose gap exceeds `half` holds no partner.
  const auto gap = [this](double uc, std::int64_t c) {
    const double g = std::max(static_cast<double>(c) - uc, uc - static_cast<double>(c + 1));
    return std::max(0.0, g - slack_);
  };
  const double half2 = half * half;
  for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
    const double gz = whole_period ? 0.0 : gap(u[2], z) * small.bz;
    if (gz * gz > half2) continue;
    const std::int64_t cz = wrap_z ? ((z % small.n[2]) + small.n[2]) % small.n[2] : z;
    for (std::int64_t cy = lo[1]; cy <= hi[1]; ++cy) {
      const double gy = gap(u[1], cy) * small.b;
      const double rest = half2 - gy * gy - gz * gz;
      if (rest < 0.0) continue;
      // The sphere's chord along this row of cells.
      const double w = std::sqrt(rest) / small.b;
      const std::int64_t x0 =
          std::max(lo[0], static_cast<std::int64_t>(std::floor(u[0] - w - slack_)));
      const std::int64_t x1 =
          std::min(hi[0], static_cast<std::int64_t>(std::floor(u[0] + w + slack_)));
      if (x0 > x1) continue;
      row(x0, x1, cy, cz);
    }
  }
}

template <class Cells>
void MultiLevelGridSearch::visit_cross(const Level& level, std::size_t slot, const Level& small,
                                       const Cells& cells, const SearchInput& in,
                                       std::vector<IndexPair>& out) {
  const Vec3& xi = level.position[slot];
  const double ri = level.radius[slot];
  const Index pi = level.order[slot];
  const SortedParticles sp = small.sorted();
  const double period = in.period_z.value_or(0.0);
  const double margin = in.margin + kTouchTolerance;
  std::uint32_t my_cells = 0, my_tests = 0;
  cross_rows(small, xi, ri, margin,
             [&](std::int64_t x0, std::int64_t x1, std::int64_t cy, std::int64_t cz) {
               if constexpr (std::is_same_v<Cells, DenseCellIndex>) {
                 my_cells += static_cast<std::uint32_t>(x1 - x0 + 1);
                 const std::uint32_t begin = cells.cell(CellCoord{x0, cy, cz}).begin;
                 const std::uint32_t end = cells.cell(CellCoord{x1, cy, cz}).end;
                 my_tests += scan_slots(sp, xi, ri, pi, begin, end, margin, period, out);
               } else {
                 for (std::int64_t cx = x0; cx <= x1; ++cx) {
                   ++my_cells;
                   CellRange r;
                   if (cells.find(CellCoord{cx, cy, cz}, r)) {
                     my_tests += scan_slots(sp, xi, ri, pi, r.begin, r.end, margin, period, out);
                   }
                 }
               }
             });
  cells_per_particle_[pi] += my_cells;
  tests_per_particle_[pi] += my_tests;
}

bool MultiLevelGridSearch::find_cell(const Level& level, const CellCoord& c, CellRange& r) {
  return level.hashed ? level.hashed_index.find(c, r) : level.dense.find(c, r);
}

GridGeometry MultiLevelGridSearch::geometry_of(const Level& level) {
  GridGeometry g;
  g.origin = level.origin;
  if (level.periodic) g.origin.z() = 0.0;  // periodic layers start at z = 0
  g.cell_xy = level.b;
  g.cell_z = level.bz;
  g.nx = level.n[0];
  g.ny = level.n[1];
  g.nz = level.n[2];
  g.hashed = level.hashed;
  g.periodic_z = level.periodic;
  return g;
}

SearchVisit MultiLevelGridSearch::visit(Index i, const SearchInput& in) const {
  std::size_t n = 0;
  for (const Level& level : levels_) n += level.order.size();
  if (in.position.size() != n) {
    throw InputError(
        fmt::format("visit: mlgrid has searched {} particles, not {}", n, in.position.size()));
  }
  if (i >= n) throw InputError(fmt::format("visit: particle {} of {}", i, n));
  std::size_t l = 0, s = 0;
  for (l = 0; l < levels_.size(); ++l) {
    const auto& order = levels_[l].order;
    const auto it = std::find(order.begin(), order.end(), i);
    if (it != order.end()) {
      s = static_cast<std::size_t>(it - order.begin());
      break;
    }
  }
  const Level& level = levels_[l];
  const Vec3 xi = level.position[s];
  const double ri = level.radius[s];
  const double margin = margin_ + kTouchTolerance;
  SearchVisit v;
  v.kind = SearchVisit::Kind::levels;
  v.particle = i;
  auto scan = [&](const Level& lv, std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t u = begin; u < end; ++u) {
      v.candidates.push_back(lv.order[u]);
      const double cut = ri + lv.radius[u] + margin;
      if (distance_squared(xi, lv.position[u], period_) <= cut * cut) {
        v.contacts.push_back(lv.order[u]);
      }
    }
  };
  auto label = [this](std::size_t k) {
    return fmt::format("level {} of {} (r <= {:.3g} mm)", k + 1, levels_.size(),
                       1000.0 * levels_[k].rmax);
  };
  VisitedCells own;
  own.label = label(l);
  own.geometry = geometry_of(level);
  own.own = level.cell[s];
  own.has_own = true;
  own.reach = level.k;
  CellRange r;
  find_cell(level, own.own, r);
  scan(level, static_cast<std::uint32_t>(s) + 1, r.end);
  const auto& offsets = level.stencil.offsets;
  for (std::uint32_t o = 0; o < level.stencil.prefix_end[level.k]; ++o) {
    CellCoord c{own.own.x + offsets[o].dx, own.own.y + offsets[o].dy, own.own.z + offsets[o].dz};
    if (!wrap(level, c)) continue;
    own.forward.push_back(c);
    if (find_cell(level, c, r)) scan(level, r.begin, r.end);
  }
  v.cells_visited = own.count();
  v.grids.push_back(std::move(own));
  for (std::size_t h = 0; h < l; ++h) {
    const Level& small = levels_[h];
    VisitedCells cross;
    cross.label = label(h);
    cross.geometry = geometry_of(small);
    cross_rows(small, xi, ri, margin,
               [&](std::int64_t x0, std::int64_t x1, std::int64_t cy, std::int64_t cz) {
                 for (std::int64_t cx = x0; cx <= x1; ++cx) {
                   const CellCoord c{cx, cy, cz};
                   cross.forward.push_back(c);
                   CellRange cr;
                   if (find_cell(small, c, cr)) scan(small, cr.begin, cr.end);
                 }
               });
    v.cells_visited += cross.count();
    v.grids.push_back(std::move(cross));
  }
  v.pairs_tested = v.candidates.size();
  v.note = fmt::format("mlgrid: level {} of {}, and {} smaller level{} from the larger side", l + 1,
                       levels_.size(), l, l == 1 ? "" : "s");
  return v;
}

std::string MultiLevelGridSearch::report() const {
  std::string text = fmt::format("{} levels:", levels_.size());
  for (const Level& level : levels_) {
    text += fmt::format(" [{} particles, cell {:.4g} m{}]", level.order.size(), level.b,
                        level.hashed ? ", hashed" : "");
  }
  return text;
}

}  // namespace drumlab
