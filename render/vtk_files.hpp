#pragma once
// Writing VTK XML files safely: binary, zlib-compressed, under a temporary name that is renamed
// into place only when the writer reports success (the .pvd collections that tie a series together:
// engine/io/paraview/pvd_series.hpp).
#include <filesystem>

class vtkDataObject;

namespace drumlab::render {

/// Writes `data` with the VTK XML writer matching its type (.vtu, .vtp, .vti) to `file`. Throws
/// InputError naming the file if it cannot be written; no file is left under the final name.
void write_vtk_xml(vtkDataObject* data, const std::filesystem::path& file);

}  // namespace drumlab::render
