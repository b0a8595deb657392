#pragma once
// Where each grid cell's particles sit in the cell-sorted order. Two storages with one lookup:
// a dense array for grids of moderate size, and an open-addressing hash of occupied cells for
// sparse inputs (particles far apart), so a huge box never allocates a huge array.
#include <cstdint>
#include <vector>

namespace drumlab {

/// A cell's slice of the sorted order: slots [begin, end); [begin, small_end) hold the particles of
/// the smallest size (only filled in when the grid needs it, method 2).
struct CellRange {
  std::uint32_t begin = 0;
  std::uint32_t small_end = 0;
  std::uint32_t end = 0;
};

struct CellCoord {
  std::int64_t x, y, z;
  friend bool operator==(const CellCoord&, const CellCoord&) = default;
};

class DenseCellIndex {
 public:
  void reset(std::int64_t nx, std::int64_t ny, std::int64_t nz);
  std::int64_t linear(const CellCoord& c) const { return c.x + nx_ * (c.y + ny_ * c.z); }
  /// Returns false for a cell outside the grid or an empty cell.
  bool find(const CellCoord& c, CellRange& r) const {
    const std::int64_t id = linear(c);
    r = cells_[static_cast<std::size_t>(id)];
    return r.end > r.begin;
  }
  /// The range of an in-grid cell (empty ranges included).
  const CellRange& cell(const CellCoord& c) const {
    return cells_[static_cast<std::size_t>(linear(c))];
  }
  CellRange& at(std::int64_t linear_id) { return cells_[static_cast<std::size_t>(linear_id)]; }

 private:
  std::int64_t nx_ = 0, ny_ = 0;
  std::vector<CellRange> cells_;
};

class HashedCellIndex {
 public:
  /// Prepares for up to `occupied` cells.
  void reset(std::size_t occupied);
  void insert(const CellCoord& c, const CellRange& r);
  bool find(const CellCoord& c, CellRange& r) const {
    for (std::size_t h = hash(c) & mask_;; h = (h + 1) & mask_) {
      const Slot& s = slots_[h];
      if (!s.used) return false;
      if (s.coord == c) {
        r = s.range;
        return true;
      }
    }
  }

 private:
  struct Slot {
    CellCoord coord{0, 0, 0};
    CellRange range;
    bool used = false;
  };
  static std::size_t hash(const CellCoord& c) {
    std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
};

}  // namespace drumlab
