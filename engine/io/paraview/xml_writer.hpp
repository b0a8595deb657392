#pragma once
// VTK's XML file formats written without VTK, for executables that must not link it (drumlab-mpi:
// see dataset.hpp): a vertex set as an UnstructuredGrid (.vtu), lines and polygons as PolyData
// (.vtp); every array in the raw appended section with UInt64 block headers, uncompressed (the
// layout VTK's own writers use with SetDataModeToAppended, EncodeAppendedDataOff and no
// compressor), written under a temporary name and renamed into place (atomic_file.hpp).
#include <filesystem>
#include <ostream>

#include "engine/io/paraview/dataset.hpp"

namespace drumlab::paraview {

/// Writes `d` to `out` as a VTK XML file (UnstructuredGrid for vertices, else PolyData).
void write_xml(const DataSet& d, std::ostream& out);

/// write_xml into `file`, atomically. Throws InputError naming the file if it cannot be written;
/// no file is left under the final name.
void write_xml_file(const DataSet& d, const std::filesystem::path& file);

}  // namespace drumlab::paraview
