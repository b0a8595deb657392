#pragma once
// The one contact-search interface every method implements: given positions and radii, find every
// pair (i, j), i < j, whose surfaces are within `margin` of each other:
//     |x_i - x_j| <= r_i + r_j + margin.
// Each method counts its work per step (cells visited, pairs tested = distances computed, pairs
// found) in total and per particle, so observers (benchmarks, the renderer, the workbench) can show
// it.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/search/cell_index.hpp"
#include "engine/search/verlet_skin.hpp"
#include "engine/types.hpp"

namespace drumlab {

struct IndexPair {
  Index i;  ///< always i < j
  Index j;
  friend bool operator==(const IndexPair&, const IndexPair&) = default;
  friend auto operator<=>(const IndexPair&, const IndexPair&) = default;
};

/// An axis-aligned box [lo, hi).
struct Box {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
};

struct SearchInput {
  std::span<const Vec3> position;
  std::span<const double> radius;
  /// Pairs within this surface gap count (m). 0 plus a round-off tolerance finds touching spheres;
  /// a Verlet skin finds neighbours-to-be.
  double margin = 0.0;
  /// If set, the grid is laid over this box (the paper's fixed grid, origin at lo) instead of the
  /// particles' bounding box. Particles must lie inside it.
  std::optional<Box> domain;
  /// If set, z is periodic with this period: positions must lie in [0, period_z) and distances use
  /// the minimum image along z (periodic drum ends).
  std::optional<double> period_z;
  /// The angle (rad) of a frame turning about the z axis (a drum's own angle): a Verlet list
  /// measures the displacements that may close its skin in that frame, where a bed turning with
  /// its drum stands still. Pair distances do not depend on it; the other methods ignore it.
  double frame_angle = 0.0;
};

struct SearchCounters {
  std::uint64_t cells_visited = 0;  ///< grid cells whose particle list was opened
  std::uint64_t pairs_tested = 0;   ///< distances computed
  std::uint64_t pairs_found = 0;    ///< pairs that passed the test
  std::uint64_t cells_total = 0;    ///< cells in the grid (0 for methods without a grid)
};

/// Wall-clock seconds of the last call, split into building the search structure (grid or cell
/// lists; a Verlet list's rebuild) and visiting the candidates (distance tests).
struct SearchTimings {
  double build = 0.0;
  double visit = 0.0;
};

/// Knobs of the search that change its speed, never its result.
struct SearchTuning {
  /// Verlet skin in units of the smallest radius: pairs within margin + skin are listed.
  double verlet_skin = kDefaultVerletSkin;
};

/// A cell grid laid by a search (for pictures and exports).
struct GridGeometry {
  Vec3 origin = Vec3::Zero();
  double cell_xy = 0.0;  ///< cell side in x and y (m)
  double cell_z = 0.0;   ///< cell side along z (the whole extent for 2D grids)
  std::int64_t nx = 0, ny = 0, nz = 0;
  bool hashed = false;  ///< occupied cells kept in a hash (sparse input) instead of a dense array
  bool periodic_z = false;
};

/// The cells of one grid that one particle's search opened.
struct VisitedCells {
  std::string label;  ///< "m2", "level 1 of 2 (r <= 5 mm)", "builder m5, last rebuild"
  GridGeometry geometry;
  CellCoord own{0, 0, 0};
  bool has_own = false;             ///< `own` is the particle's own cell in this grid (visited)
  std::vector<CellCoord> forward;   ///< cells visited besides the own cell (half shell, or the
                                    ///< cells of a smaller level within reach)
  std::vector<CellCoord> backward;  ///< method 2: far backward cells scanned for smallest partners
  int reach = 0;                    ///< forward reach in cells (0 where there is no stencil)
  std::size_t count() const { return (has_own ? 1 : 0) + forward.size() + backward.size(); }
};

/// One particle's search, replayed on demand for pictures, teaching and the workbench: what the
/// method visited for it, the candidates it tested and the pairs it found. A grid or brute force
/// tests each pair from one of its two particles only (half shells; j > i), so a particle's
/// contacts found by its partners' searches are not among its own candidates; a Verlet list's
/// candidates are all of the particle's listed partners.
struct SearchVisit {
  enum class Kind : std::uint8_t {
    cells,   ///< one cell grid (m1..m5): `grids` holds it
    levels,  ///< a multi-level grid: `grids` holds the levels it visited, its own level first
    list,    ///< a Verlet list: candidates are its listed partners; `grids` the builder's cells
             ///< of the last rebuild where they are still valid, else empty
    all,     ///< brute force: no cells, every later particle in storage order
  };
  Kind kind = Kind::all;
  Index particle = 0;
  std::vector<VisitedCells> grids;
  std::vector<Index> candidates;  ///< grids, brute force: the partners this particle's search
                                  ///< tested; a Verlet list: every listed partner of it
  std::vector<Index> contacts;    ///< candidates within r_i + r_j + margin
  /// Distances this particle's own search computes, as pairs_tested_per_particle() counts them
  /// (candidates.size(), except for a Verlet list: the pairs listed under i, with j > i).
  std::size_t pairs_tested = 0;
  /// Cells opened, as cells_visited_per_particle() counts them (0 for a list or brute force).
  std::size_t cells_visited = 0;
  std::string note;  ///< one line for people ("tests all N-1 = 501 others, 250 of them itself")
};

class ContactSearch {
 public:
  virtual ~ContactSearch() = default;

  /// Short name used on the command line and in scenes ("brute", "m1" ... "m5").
  virtual std::string_view name() const = 0;
  /// One line saying what the method does.
  virtual std::string_view description() const = 0;

  /// Replaces `out` with every pair within the margin, each once with i < j, in no particular
  /// order. Throws InputError for input the method cannot handle (non-finite coordinates, a grid
  /// too large to index); never returns a partial answer.
  virtual void find_pairs(const SearchInput& in, std::vector<IndexPair>& out) = 0;

  /// Replays the search of particle i (storage index) on the positions `in` (the current ones,
  /// which for a grid must be those of its last call: it reuses the grid laid then). Read-only and
  /// for one particle (O(N) at most): never called in the step loop, it costs the step nothing.
  /// Throws InputError if i is out of range or the method has not run on these particles yet.
  virtual SearchVisit visit(Index i, const SearchInput& in) const = 0;

  /// Method-specific figures for people (e.g. Verlet rebuilds); empty if there are none.
  virtual std::string report() const { return {}; }

  /// Cell side used in the last call (m), 0 for methods without a grid.
  virtual double cell_size() const { return 0.0; }

  const SearchCounters& counters() const { return counters_; }
  const SearchTimings& timings() const { return timings_; }
  /// Cells visited and pairs tested in the last call, by the particle whose search did the work.
  std::span<const std::uint32_t> cells_visited_per_particle() const { return cells_per_particle_; }
  std::span<const std::uint32_t> pairs_tested_per_particle() const { return tests_per_particle_; }

 protected:
  void reset_counters(std::size_t n);

  SearchCounters counters_;
  SearchTimings timings_;
  std::vector<std::uint32_t> cells_per_particle_;
  std::vector<std::uint32_t> tests_per_particle_;
};

/// Names accepted by make_search, in a stable order.
std::vector<std::string> search_method_names();
/// Creates a search by name. Throws InputError naming the unknown method and the valid ones.
std::unique_ptr<ContactSearch> make_search(std::string_view name, const SearchTuning& tuning = {});

/// Distance tolerance that makes touching spheres count as a contact (m).
inline constexpr double kTouchTolerance = 1e-9;

}  // namespace drumlab
