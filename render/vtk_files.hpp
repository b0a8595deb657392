#pragma once
// Writing VTK XML files safely: binary, zlib-compressed, under a temporary name that is renamed
// into place only when the writer reports success; and the .pvd collection that ties a time series
// together for ParaView.
#include <filesystem>
#include <string>
#include <vector>

class vtkDataObject;

namespace drumlab::render {

/// Writes `data` with the VTK XML writer matching its type (.vtu, .vtp, .vti) to `file`. Throws
/// InputError naming the file if it cannot be written; no file is left under the final name.
void write_vtk_xml(vtkDataObject* data, const std::filesystem::path& file);

struct PvdEntry {
  double time = 0.0;
  std::string file;  ///< relative to the .pvd
};

/// The text of a VTK "Collection" file (ParaView's .pvd).
std::string pvd_text(const std::vector<PvdEntry>& entries);

}  // namespace drumlab::render
