#pragma once
// A dataset for ParaView described without VTK: points, cells and named arrays, the way VTK's XML
// formats hold them. The datasets of the VTU/PVD series (frame_datasets.hpp) are built once in
// these terms; render/ turns them into VTK objects and writes them with VTK's XML writers, and an
// executable that must not link VTK (drumlab-mpi: its parallel HDF5 and VTK's serial one clash)
// writes the same arrays with xml_writer.hpp.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "engine/types.hpp"

namespace drumlab::paraview {

/// One named array: `components` values per tuple, of one of VTK's types Float64, UInt32, UInt8.
struct DataArray {
  std::string name;
  int components = 1;
  std::variant<std::vector<double>, std::vector<std::uint32_t>, std::vector<std::uint8_t>> values;

  std::size_t size() const {
    return std::visit([](const auto& v) { return v.size(); }, values);
  }
  std::size_t tuples() const { return size() / static_cast<std::size_t>(components); }
};

template <class T>
DataArray make_array(std::string name, std::vector<T> values, int components = 1) {
  return DataArray{std::move(name), components, std::move(values)};
}

/// What the cells are: one vertex per point (an unstructured grid, .vtu), or lines or polygons
/// given by `connectivity` and `offsets` (poly data, .vtp).
enum class CellKind : std::uint8_t { vertices, lines, polygons };

struct DataSet {
  CellKind cells = CellKind::vertices;
  std::vector<Vec3> points;
  /// Lines and polygons: the point ids of every cell, one after the other, and where each cell
  /// ends in `connectivity` (VTK's "offsets"). Empty for vertices.
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<DataArray> point_data, cell_data, field_data;
  /// The active scalars / vectors: point data of a vertex set, cell data otherwise ("" for none).
  std::string active_scalars, active_vectors;

  std::size_t cell_count() const {
    return cells == CellKind::vertices ? points.size() : offsets.size();
  }
  /// Adds a cell of the given point ids (lines and polygons).
  void add_cell(std::initializer_list<std::int64_t> ids) {
    connectivity.insert(connectivity.end(), ids);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
};

}  // namespace drumlab::paraview
