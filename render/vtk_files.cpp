#include "render/vtk_files.hpp"

#include <unistd.h>

#include <system_error>

#include <fmt/format.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLRectilinearGridWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "engine/types.hpp"

namespace drumlab::render {
namespace {

/// VTK's own multi-line error output is replaced by our one-line InputError.
class QuietVtk {
 public:
  QuietVtk() : was_(vtkObject::GetGlobalWarningDisplay()) { vtkObject::GlobalWarningDisplayOff(); }
  ~QuietVtk() { vtkObject::SetGlobalWarningDisplay(was_); }
  QuietVtk(const QuietVtk&) = delete;
  QuietVtk& operator=(const QuietVtk&) = delete;

 private:
  vtkTypeBool was_;
};

template <class Writer>
bool write_with(vtkDataObject* data, const std::filesystem::path& file) {
  const QuietVtk quiet;
  vtkNew<Writer> w;
  w->SetInputData(data);
  w->SetFileName(file.c_str());
  // Appended raw binary (what ParaView itself writes), not inline: on a write error VTK 9.1's
  // inline path frees position arrays it never allocated (vtkXMLUnstructuredDataWriter::
  // WriteAPiece -> DeletePositionArrays on OutOfDiskSpaceError), which crashed the full-disk test
  // depending on what the heap held.
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  w->SetCompressorTypeToZLib();
  w->SetHeaderTypeToUInt64();
  return w->Write() == 1 && w->GetErrorCode() == 0;
}

}  // namespace

void write_vtk_xml(vtkDataObject* data, const std::filesystem::path& file) {
  namespace fs = std::filesystem;
  const fs::path tmp = file.string() + fmt::format(".tmp-{}", ::getpid());
  bool ok = false;
  if (vtkUnstructuredGrid::SafeDownCast(data)) {
    ok = write_with<vtkXMLUnstructuredGridWriter>(data, tmp);
  } else if (vtkPolyData::SafeDownCast(data)) {
    ok = write_with<vtkXMLPolyDataWriter>(data, tmp);
  } else if (vtkImageData::SafeDownCast(data)) {
    ok = write_with<vtkXMLImageDataWriter>(data, tmp);
  } else if (vtkRectilinearGrid::SafeDownCast(data)) {
    ok = write_with<vtkXMLRectilinearGridWriter>(data, tmp);
  } else {
    throw std::logic_error("write_vtk_xml: unsupported data type");
  }
  std::error_code ec;
  if (!ok) {
    fs::remove(tmp, ec);
    throw InputError(
        fmt::format("{}: cannot write (does the directory exist and is it writable? disk full?)",
                    file.string()));
  }
  fs::rename(tmp, file, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError(fmt::format("{}: cannot rename into place: {}", file.string(), ec.message()));
  }
}

}  // namespace drumlab::render
