#include "engine/mesh/stl_file.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"

namespace drumlab {
namespace {

std::vector<std::array<Vec3, 3>> read_binary(std::string_view bytes, const std::string& name) {
  std::uint32_t n = 0;
  std::memcpy(&n, bytes.data() + 80, 4);
  std::vector<std::array<Vec3, 3>> out(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* rec = bytes.data() + 84 + 50 * static_cast<std::size_t>(t) + 12;  // after normal
    for (int k = 0; k < 3; ++k) {
      float v[3];
      std::memcpy(v, rec + 12 * k, 12);
      out[t][static_cast<std::size_t>(k)] = Vec3(v[0], v[1], v[2]);
    }
  }
  if (n == 0) throw InputError(fmt::format("{}: the STL file has no triangle", name));
  return out;
}

std::vector<std::array<Vec3, 3>> read_ascii(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  std::vector<std::array<Vec3, 3>> out;
  std::string word;
  std::size_t corners = 0;
  std::array<Vec3, 3> facet;
  bool solid = false;
  while (in >> word) {
    if (word == "solid" && !solid) {
      solid = true;
      std::string rest;
      std::getline(in, rest);  // the solid's name
      continue;
    }
    if (word == "vertex") {
      double x = 0, y = 0, z = 0;
      if (!(in >> x >> y >> z)) {
        throw InputError(
            fmt::format("{}: facet {}: a vertex without three numbers", name, out.size() + 1));
      }
      if (corners == 3) {
        throw InputError(
            fmt::format("{}: facet {} has more than 3 vertices", name, out.size() + 1));
      }
      facet[corners++] = Vec3(x, y, z);
    } else if (word == "endfacet") {
      if (corners != 3) {
        throw InputError(
            fmt::format("{}: facet {} has {} vertices, not 3", name, out.size() + 1, corners));
      }
      out.push_back(facet);
      corners = 0;
    }
  }
  if (!solid) throw InputError(fmt::format("{}: neither a binary nor an ASCII STL file", name));
  if (corners != 0) {
    throw InputError(
        fmt::format("{}: the file ends inside facet {} (truncated?)", name, out.size() + 1));
  }
  if (text.find("endsolid") == std::string::npos) {
    throw InputError(fmt::format("{}: no 'endsolid' (truncated?)", name));
  }
  if (out.empty()) throw InputError(fmt::format("{}: the STL file has no triangle", name));
  return out;
}

}  // namespace

std::vector<std::array<Vec3, 3>> read_stl(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the STL file", file.string()));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_stl(bytes, file.string());
}

std::vector<std::array<Vec3, 3>> parse_stl(std::string_view bytes, const std::string& name) {
  std::uint32_t n = 0;
  if (bytes.size() >= 84) std::memcpy(&n, bytes.data() + 80, 4);
  const std::uint64_t binary_size = 84 + 50 * static_cast<std::uint64_t>(n);
  if (bytes.size() >= 84 && bytes.size() == binary_size) return read_binary(bytes, name);
  if (bytes.substr(0, 5) == "solid") return read_ascii(std::string(bytes), name);
  if (bytes.size() >= 84) {
    throw InputError(fmt::format(
        "{}: a binary STL of {} triangles needs {} bytes, the file has {} (truncated or damaged)",
        name, n, binary_size, bytes.size()));
  }
  throw InputError(fmt::format("{}: {} bytes: too short for an STL file", name, bytes.size()));
}

void write_stl(const TriangleMesh& mesh, const std::filesystem::path& file) {
  write_file_atomically(file, [&](std::ostream& out) {
    char header[80] = {};
    const std::string title = "drumlab mesh " + mesh.source;
    std::memcpy(header, title.data(), std::min<std::size_t>(title.size(), 79));
    out.write(header, 80);
    const auto n = static_cast<std::uint32_t>(mesh.size());
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (std::size_t t = 0; t < mesh.size(); ++t) {
      float rec[12];
      for (int k = 0; k < 3; ++k) rec[k] = static_cast<float>(mesh.normals[t][k]);
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 3; ++k) rec[3 + 3 * c + k] = static_cast<float>(mesh.corner(t, c)[k]);
      }
      out.write(reinterpret_cast<const char*>(rec), sizeof rec);
      const std::uint16_t attribute = 0;
      out.write(reinterpret_cast<const char*>(&attribute), 2);
    }
  });
}

}  // namespace drumlab
