#include "engine/search/cell_index.hpp"

#include "engine/parallel_copy.hpp"

namespace drumlab {

void DenseCellIndex::reset(std::int64_t nx, std::int64_t ny, std::int64_t nz) {
  nx_ = nx;
  ny_ = ny;
  // The grid follows the bed's bounding box, which breathes as the drum turns: a new largest
  // grid takes half as many cells again, so that the steps after it do not allocate again.
  const auto size = static_cast<std::size_t>(nx * ny * nz);
  if (size > cells_.capacity()) cells_.reserve(size + size / 2);
  parallel_fill(cells_, size, CellRange{});
}

void HashedCellIndex::reset(std::size_t occupied) {
  std::size_t capacity = 16;
  while (capacity < 2 * occupied) capacity *= 2;
  slots_.assign(capacity, Slot{});
  mask_ = capacity - 1;
}

void HashedCellIndex::insert(const CellCoord& c, const CellRange& r) {
  std::size_t h = hash(c) & mask_;
  while (slots_[h].used && !(slots_[h].coord == c)) h = (h + 1) & mask_;
  slots_[h] = Slot{c, r, true};
}

}  // namespace drumlab
