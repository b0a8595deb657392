#include "engine/search/cell_grid.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numeric>
#include <type_traits>

#include <fmt/format.h>

#include "engine/search/grid_axes.hpp"
#include "engine/search/search_input.hpp"
#include "engine/search/search_methods.hpp"
#include "engine/threads.hpp"

namespace drumlab {

namespace {

/// A dense array is used while it costs at most this many cells per particle (plus a floor).
constexpr double kDenseCellsPerParticle = 64.0;
constexpr double kDenseCellFloor = 4194304.0;  // 2^22

}  // namespace

CellGridConfig paper_method(int method) {
  if (method < 1 || method > 5) {
    throw InputError(fmt::format("paper method must be 1..5, got {}", method));
  }
  // Name, description, grid and cell side from the table of methods; the stencil per method.
  static constexpr const char* kNames[] = {"m1", "m2", "m3", "m4", "m5"};
  const SearchMethodInfo& m = search_method(kNames[method - 1]);
  CellGridConfig c;
  c.name = kNames[method - 1];
  c.description = m.description.data();  // a literal: null-terminated
  c.three_d = m.grid == SearchGrid::three_d;
  c.cell_from_min_radius = m.cell == CellRule::min_radius;
  c.per_size_stencil = method <= 3;
  c.skip_far_for_smallest = method == 2;
  return c;
}

void CellGridSearch::find_pairs(const SearchInput& in, std::vector<IndexPair>& out) {
  const auto t0 = SearchClock::now();
  validate_search_input(in);
  const std::size_t n = in.position.size();
  reset_counters(n);
  out.clear();
  timings_ = {};
  if (n == 0) return;
  margin_ = in.margin;
  period_ = in.period_z.value_or(0.0);
  lay_grid(in);
  sort_into_cells(in);
  if (geometry_.hashed) build_hashed();
  timings_.build = seconds_since(t0);
  const auto t1 = SearchClock::now();
  if (geometry_.hashed) {
    visit_all(hashed_, in, out);
  } else {
    visit_all(dense_, in, out);
  }
  timings_.visit = seconds_since(t1);
  counters_.pairs_found = out.size();
}

void CellGridSearch::lay_grid(const SearchInput& in) {
  const std::size_t n = in.position.size();
  const auto [rmin_it, rmax_it] = std::minmax_element(in.radius.begin(), in.radius.end());
  const double rmin = *rmin_it;
  const double rmax = *rmax_it;
  const double period = in.period_z.value_or(0.0);

  const Box bounds = search_bounds(in);
  const Vec3& lo = bounds.lo;
  // The cell is widened by the margin so a pair at exactly k nominal cells still fits in k cells.
  const double b = (config_.cell_from_min_radius ? rmin : rmax) + in.margin + kTouchTolerance;
  const GridAxes axes(bounds, b, config_.name);
  auto cells_for = [&](double reach) { return axes.reach_cells(reach); };

  reach_.resize(n);
  int kmax = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double reach =
        (config_.per_size_stencil ? in.radius[i] + rmax : 2.0 * rmax) + in.margin + kTouchTolerance;
    reach_[i] = cells_for(reach);
    kmax = std::max(kmax, reach_[i]);
  }
  small_radius_ = rmin * (1.0 + 1e-12);
  if (config_.skip_far_for_smallest) {
    k_small_ = cells_for(2.0 * rmin + in.margin + kTouchTolerance);
    reach_back_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      reach_back_[i] = cells_for(rmin + in.radius[i] + in.margin + kTouchTolerance);
    }
  }

  GridGeometry g;
  g.origin = lo;
  g.cell_xy = b;
  g.nx = axes.cells(0);
  g.ny = axes.cells(1);
  g.periodic_z = period > 0.0;
  if (!config_.three_d) {
    g.nz = 1;
    g.cell_z = bounds.hi.z() - lo.z();
  } else if (g.periodic_z) {
    // Cells must tile the period exactly; with fewer than 2k+1 layers the wrapped stencil would
    // visit a layer twice, so such a thin periodic slab is searched as one layer.
    g.nz = static_cast<std::int64_t>(period / b);
    if (g.nz < 2 * kmax + 1) g.nz = 1;
    g.cell_z = period / static_cast<double>(g.nz);
  } else {
    g.nz = axes.cells(2);
    g.cell_z = b;
  }
  const double total =
      static_cast<double>(g.nx) * static_cast<double>(g.ny) * static_cast<double>(g.nz);
  g.hashed = total > kDenseCellsPerParticle * static_cast<double>(n) + kDenseCellFloor;
  geometry_ = g;
  counters_.cells_total = static_cast<std::uint64_t>(total);

  const bool three_d = config_.three_d && g.nz > 1;
  if (stencil_.kmax() != kmax || stencil_three_d_ != three_d) {
    stencil_ = HalfStencil(kmax, three_d);
    stencil_three_d_ = three_d;
  }
}

void CellGridSearch::sort_into_cells(const SearchInput& in) {
  const std::size_t n = in.position.size();
  const GridGeometry& g = geometry_;
  cell_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 u = (in.position[i] - g.origin) / g.cell_xy;
    CellCoord c{std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(u.x())), 0, g.nx - 1),
                std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(u.y())), 0, g.ny - 1),
                0};
    if (g.nz > 1) {
      const double uz = (in.position[i].z() - g.origin.z()) / g.cell_z;
      c.z = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(uz)), 0, g.nz - 1);
    }
    cell_[i] = c;
  }
  // Smallest-size particles first within a cell (method 2 scans only that segment backwards).
  auto key_less = [this, &in](Index a, Index b) {
    const CellCoord& ca = cell_[a];
    const CellCoord& cb = cell_[b];
    if (ca.z != cb.z) return ca.z < cb.z;
    if (ca.y != cb.y) return ca.y < cb.y;
    if (ca.x != cb.x) return ca.x < cb.x;
    const bool small_a = in.radius[a] <= small_radius_;
    const bool small_b = in.radius[b] <= small_radius_;
    if (small_a != small_b) return small_a;
    return a < b;
  };
  order_.resize(n);
  if (g.hashed) {
    std::iota(order_.begin(), order_.end(), Index{0});
    std::sort(order_.begin(), order_.end(), key_less);
  } else {
    // Counting sort by linear cell id: O(N + cells).
    dense_.reset(g.nx, g.ny, g.nz);
    for (std::size_t i = 0; i < n; ++i) ++dense_.at(dense_.linear(cell_[i])).end;
    std::uint32_t running = 0;
    const std::int64_t cells = g.nx * g.ny * g.nz;
    for (std::int64_t c = 0; c < cells; ++c) {
      CellRange& r = dense_.at(c);
      r.begin = running;
      running += r.end;
      r.small_end = r.begin;  // fill cursor
      r.end = r.begin;
    }
    for (int pass = 0; pass < 2; ++pass) {  // smallest-size particles first, stable otherwise
      for (std::size_t i = 0; i < n; ++i) {
        if ((in.radius[i] <= small_radius_) != (pass == 0)) continue;
        CellRange& r = dense_.at(dense_.linear(cell_[i]));
        order_[r.end++] = static_cast<Index>(i);
        if (pass == 0) r.small_end = r.end;
      }
    }
  }
  sorted_position_.resize(n);
  sorted_radius_.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    sorted_position_[s] = in.position[order_[s]];
    sorted_radius_[s] = in.radius[order_[s]];
  }
}

void CellGridSearch::build_hashed() {
  const std::size_t n = order_.size();
  std::size_t occupied = 0;
  for (std::size_t s = 1; s <= n; ++s) {
    if (s == n || !(cell_[order_[s]] == cell_[order_[s - 1]])) ++occupied;
  }
  hashed_.reset(occupied);
  for (std::size_t s = 0; s < n;) {
    std::size_t e = s + 1;
    while (e < n && cell_[order_[e]] == cell_[order_[s]]) ++e;
    std::uint32_t small_end = static_cast<std::uint32_t>(s);
    while (small_end < e && sorted_radius_[small_end] <= small_radius_) ++small_end;
    hashed_.insert(cell_[order_[s]], CellRange{static_cast<std::uint32_t>(s), small_end,
                                               static_cast<std::uint32_t>(e)});
    s = e;
  }
}

bool CellGridSearch::wrap(CellCoord& c) const {
  const GridGeometry& g = geometry_;
  if (c.x < 0 || c.x >= g.nx || c.y < 0 || c.y >= g.ny) return false;
  if (g.periodic_z && g.nz > 1) {  // |dz| <= k < nz, so one wrap suffices
    if (c.z < 0) {
      c.z += g.nz;
    } else if (c.z >= g.nz) {
      c.z -= g.nz;
    }
    return true;
  }
  return c.z >= 0 && c.z < g.nz;
}

template <class Cells>
void CellGridSearch::visit_all(const Cells& cells, const SearchInput& in,
                               std::vector<IndexPair>& out) {
  const std::size_t n = order_.size();
  const double period = in.period_z.value_or(0.0);
  const double margin = in.margin + kTouchTolerance;
  const std::vector<CellOffset>& offsets = stencil_.offsets;
  const SortedParticles sorted{sorted_position_.data(), sorted_radius_.data(), order_.data()};
  std::uint64_t cells_visited = 0, pairs_tested = 0;
  // Each thread takes a contiguous block of slots and collects its pairs; the blocks are joined
  // in order. Counters per particle are written by the one thread that owns the particle.
  const int threads = slices_.prepare(max_threads());
  const auto slots = static_cast<std::int64_t>(n);
#pragma omp parallel num_threads(threads) reduction(+ : cells_visited, pairs_tested)
  {
    std::vector<IndexPair>& mine = slices_.slice(thread_number());
#pragma omp for schedule(static)
    for (std::int64_t ss = 0; ss < slots; ++ss) {
      const auto s = static_cast<std::size_t>(ss);
      const Vec3 xi = sorted_position_[s];
      const double ri = sorted_radius_[s];
      const Index pi = order_[s];
      const CellCoord ci = cell_[pi];
      std::uint32_t my_cells = 1, my_tests = 0;

      auto scan = [&](std::uint32_t begin, std::uint32_t end) {
        my_tests += scan_slots(sorted, xi, ri, pi, begin, end, margin, period, mine);
      };

      CellRange r;
      cells.find(ci, r);
      scan(static_cast<std::uint32_t>(s) + 1, r.end);  // own cell: partners later in the order

      const bool small = ri <= small_radius_;
      const bool skip = config_.skip_far_for_smallest;
      const int k_forward = (skip && small) ? std::min(k_small_, reach_[pi]) : reach_[pi];
      if constexpr (std::is_same_v<Cells, DenseCellIndex>) {
        // Rows of cells are contiguous in the sorted order: two lookups per row.
        for (const StencilRow& row : stencil_.rows[k_forward]) {
          CellCoord c{0, ci.y + row.dy, ci.z + row.dz};
          if (!wrap(c)) continue;
          const std::int64_t x0 = std::max<std::int64_t>(ci.x + row.dx_lo, 0);
          const std::int64_t x1 = std::min<std::int64_t>(ci.x + row.dx_hi, geometry_.nx - 1);
          if (x0 > x1) continue;
          my_cells += static_cast<std::uint32_t>(x1 - x0 + 1);
          c.x = x0;
          const std::uint32_t begin = cells.cell(c).begin;
          c.x = x1;
          scan(begin, cells.cell(c).end);
        }
      } else {
        for (std::uint32_t o = 0; o < stencil_.prefix_end[k_forward]; ++o) {
          CellCoord c{ci.x + offsets[o].dx, ci.y + offsets[o].dy, ci.z + offsets[o].dz};
          if (!wrap(c)) continue;
          ++my_cells;
          if (cells.find(c, r)) scan(r.begin, r.end);
        }
      }
      if (skip && !small && reach_back_[pi] > k_small_) {
        // Far ring of the backward half, smallest-size partners only (they skipped it).
        for (std::uint32_t o = stencil_.prefix_end[k_small_];
             o < stencil_.prefix_end[reach_back_[pi]]; ++o) {
          CellCoord c{ci.x - offsets[o].dx, ci.y - offsets[o].dy, ci.z - offsets[o].dz};
          if (!wrap(c)) continue;
          ++my_cells;
          if (cells.find(c, r)) scan(r.begin, r.small_end);
        }
      }
      cells_per_particle_[pi] = my_cells;
      tests_per_particle_[pi] = my_tests;
      cells_visited += my_cells;
      pairs_tested += my_tests;
    }
  }
  slices_.join(out);
  counters_.cells_visited = cells_visited;
  counters_.pairs_tested = pairs_tested;
}

bool CellGridSearch::find_cell(const CellCoord& c, CellRange& r) const {
  return geometry_.hashed ? hashed_.find(c, r) : dense_.find(c, r);
}

SearchTrace CellGridSearch::trace(Index i) const {
  const std::size_t n = order_.size();
  if (i >= n) throw InputError(fmt::format("trace: particle {} of {}", i, n));
  const std::size_t s =
      static_cast<std::size_t>(std::find(order_.begin(), order_.end(), i) - order_.begin());
  const Vec3 xi = sorted_position_[s];
  const double ri = sorted_radius_[s];
  const double margin = margin_ + kTouchTolerance;
  SearchTrace t;
  t.own = cell_[i];
  auto scan = [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t u = begin; u < end; ++u) {
      const Index pj = order_[u];
      t.candidates.push_back(pj);
      const double cut = ri + sorted_radius_[u] + margin;
      if (distance_squared(xi, sorted_position_[u], period_) <= cut * cut) t.contacts.push_back(pj);
    }
  };
  CellRange r;
  find_cell(t.own, r);
  scan(static_cast<std::uint32_t>(s) + 1, r.end);
  const bool small = ri <= small_radius_;
  const bool skip = config_.skip_far_for_smallest;
  t.reach = (skip && small) ? std::min(k_small_, reach_[i]) : reach_[i];
  const std::vector<CellOffset>& offsets = stencil_.offsets;
  for (std::uint32_t o = 0; o < stencil_.prefix_end[t.reach]; ++o) {
    CellCoord c{t.own.x + offsets[o].dx, t.own.y + offsets[o].dy, t.own.z + offsets[o].dz};
    if (!wrap(c)) continue;
    t.forward.push_back(c);
    if (find_cell(c, r)) scan(r.begin, r.end);
  }
  if (skip && !small && reach_back_[i] > k_small_) {
    for (std::uint32_t o = stencil_.prefix_end[k_small_]; o < stencil_.prefix_end[reach_back_[i]];
         ++o) {
      CellCoord c{t.own.x - offsets[o].dx, t.own.y - offsets[o].dy, t.own.z - offsets[o].dz};
      if (!wrap(c)) continue;
      t.backward.push_back(c);
      if (find_cell(c, r)) scan(r.begin, r.small_end);
    }
  }
  return t;
}

SearchVisit CellGridSearch::visit(Index i, const SearchInput& in) const {
  if (in.position.size() != order_.size()) {
    throw InputError(fmt::format("visit: {} has searched {} particles, not {}", config_.name,
                                 order_.size(), in.position.size()));
  }
  SearchTrace t = trace(i);
  SearchVisit v;
  v.kind = SearchVisit::Kind::cells;
  v.particle = i;
  VisitedCells cells;
  cells.label = config_.name;
  cells.geometry = geometry_;
  cells.own = t.own;
  cells.has_own = true;
  cells.forward = std::move(t.forward);
  cells.backward = std::move(t.backward);
  cells.reach = t.reach;
  v.cells_visited = cells.count();
  v.grids.push_back(std::move(cells));
  v.candidates = std::move(t.candidates);
  v.pairs_tested = v.candidates.size();
  v.contacts = std::move(t.contacts);
  return v;
}

}  // namespace drumlab
