#include "engine/io/paraview/xml_writer.hpp"

#include <bit>
#include <cstring>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"

namespace drumlab::paraview {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the files declare byte_order=\"LittleEndian\"");

const char* type_name(const std::vector<double>&) {
  return "Float64";
}
const char* type_name(const std::vector<std::uint32_t>&) {
  return "UInt32";
}
const char* type_name(const std::vector<std::uint8_t>&) {
  return "UInt8";
}
const char* type_name(const std::vector<std::int64_t>&) {
  return "Int64";
}

/// The appended section: each array's bytes after a UInt64 byte count; `offset` is where the
/// next block starts, as the XML's offset attributes count it (from the byte after '_').
class Appended {
 public:
  template <class T>
  std::uint64_t add(const T* data, std::size_t count) {
    const std::uint64_t at = offset_;
    blocks_.push_back({reinterpret_cast<const char*>(data), count * sizeof(T)});
    offset_ += sizeof(std::uint64_t) + count * sizeof(T);
    return at;
  }
  void write(std::ostream& out) const {
    out << "  <AppendedData encoding=\"raw\">\n   _";
    for (const auto& [data, bytes] : blocks_) {
      const std::uint64_t n = bytes;
      out.write(reinterpret_cast<const char*>(&n), sizeof n);
      out.write(data, static_cast<std::streamsize>(bytes));
    }
    out << "\n  </AppendedData>\n";
  }

 private:
  std::vector<std::pair<const char*, std::size_t>> blocks_;
  std::uint64_t offset_ = 0;
};

class XmlBody {
 public:
  explicit XmlBody(Appended& appended) : appended_(appended) {}

  void array(const DataArray& a, bool field) {
    std::visit([&](const auto& v) { element(a.name, v, a.components, field ? a.tuples() : 0); },
               a.values);
  }
  template <class T>
  void element(const std::string& name, const std::vector<T>& v, int components,
               std::size_t field_tuples = 0) {
    text_ += fmt::format("        <DataArray type=\"{}\" Name=\"{}\"", type_name(v), name);
    if (components != 1) text_ += fmt::format(" NumberOfComponents=\"{}\"", components);
    if (field_tuples != 0) text_ += fmt::format(" NumberOfTuples=\"{}\"", field_tuples);
    text_ +=
        fmt::format(" format=\"appended\" offset=\"{}\"/>\n", appended_.add(v.data(), v.size()));
  }
  void points(const std::vector<Vec3>& p) {
    text_ += "      <Points>\n";
    text_ += fmt::format(
        "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
        "format=\"appended\" offset=\"{}\"/>\n",
        appended_.add(p.empty() ? nullptr : p.front().data(), 3 * p.size()));
    text_ += "      </Points>\n";
  }
  void data(const char* section, const std::vector<DataArray>& arrays, const DataSet& d) {
    std::string attributes;
    if (!d.active_scalars.empty()) attributes += fmt::format(" Scalars=\"{}\"", d.active_scalars);
    if (!d.active_vectors.empty()) attributes += fmt::format(" Vectors=\"{}\"", d.active_vectors);
    const bool active = (d.cells == CellKind::vertices) == (std::string(section) == "PointData");
    text_ += fmt::format("      <{}{}>\n", section, active ? attributes : std::string());
    for (const DataArray& a : arrays) array(a, false);
    text_ += fmt::format("      </{}>\n", section);
  }
  void line(const std::string& s) { text_ += s; }
  const std::string& text() const { return text_; }

 private:
  Appended& appended_;
  std::string text_;
};

}  // namespace

void write_xml(const DataSet& d, std::ostream& out) {
  const bool grid = d.cells == CellKind::vertices;
  const char* type = grid ? "UnstructuredGrid" : "PolyData";
  const std::size_t n = d.points.size();
  const std::size_t cells = d.cell_count();
  Appended appended;
  XmlBody body(appended);
  body.line(fmt::format("  <{}>\n", type));
  if (!d.field_data.empty()) {
    body.line("    <FieldData>\n");
    for (const DataArray& a : d.field_data) body.array(a, true);
    body.line("    </FieldData>\n");
  }
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  if (grid) {
    body.line(fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n));
    connectivity.resize(n);
    offsets.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      connectivity[i] = static_cast<std::int64_t>(i);
      offsets[i] = static_cast<std::int64_t>(i + 1);
    }
    types.assign(n, 1);  // VTK_VERTEX
  } else {
    const bool lines = d.cells == CellKind::lines;
    body.line(
        fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
                    "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
                    n, lines ? cells : 0, lines ? 0 : cells));
  }
  body.data("PointData", d.point_data, d);
  body.data("CellData", d.cell_data, d);
  body.points(d.points);
  const char* cell_section = grid ? "Cells" : d.cells == CellKind::lines ? "Lines" : "Polys";
  body.line(fmt::format("      <{}>\n", cell_section));
  const std::vector<std::int64_t>& cell_points = grid ? connectivity : d.connectivity;
  const std::vector<std::int64_t>& cell_ends = grid ? offsets : d.offsets;
  body.element("connectivity", cell_points, 1);
  body.element("offsets", cell_ends, 1);
  if (grid) body.element("types", types, 1);
  body.line(fmt::format("      </{}>\n", cell_section));
  body.line(fmt::format("    </Piece>\n  </{}>\n", type));
  out << "<?xml version=\"1.0\"?>\n"
      << fmt::format(
             "<VTKFile type=\"{}\" version=\"1.0\" byte_order=\"LittleEndian\" "
             "header_type=\"UInt64\">\n",
             type)
      << body.text();
  appended.write(out);
  out << "</VTKFile>\n";
}

void write_xml_file(const DataSet& d, const std::filesystem::path& file) {
  write_file_atomically(file, [&](std::ostream& out) { write_xml(d, out); });
}

}  // namespace drumlab::paraview
