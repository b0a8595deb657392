#include "render/frame_writer.hpp"

#include <system_error>

#include <fmt/format.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkUnsignedCharArray.h>

#include "engine/io/atomic_file.hpp"
#include "engine/types.hpp"

namespace drumlab::render {

void write_png(const Image& image, const std::filesystem::path& file) {
  vtkNew<vtkImageData> data;
  data->SetDimensions(image.width, image.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* dst = static_cast<unsigned char*>(data->GetScalarPointer());
  const std::size_t row = 3 * static_cast<std::size_t>(image.width);
  for (int y = 0; y < image.height; ++y) {  // VTK images start at the bottom row
    std::copy_n(image.rgb.data() + row * static_cast<std::size_t>(image.height - 1 - y), row,
                dst + row * static_cast<std::size_t>(y));
  }
  vtkNew<vtkPNGWriter> png;
  png->SetInputData(data);
  png->WriteToMemoryOn();
  png->Write();
  vtkUnsignedCharArray* bytes = png->GetResult();
  if (bytes == nullptr || bytes->GetNumberOfValues() == 0) {
    throw InputError(fmt::format("{}: PNG encoding failed", file.string()));
  }
  write_file_atomically(file, [bytes](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes->GetPointer(0)),
              static_cast<std::streamsize>(bytes->GetNumberOfValues()));
  });
}

FrameWriter::FrameWriter(std::filesystem::path directory) : directory_(std::move(directory)) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec || !std::filesystem::is_directory(directory_)) {
    throw InputError(fmt::format("{}: cannot create the output directory ({})", directory_.string(),
                                 ec ? ec.message() : "not a directory"));
  }
}

std::filesystem::path FrameWriter::write(const Image& image, std::uint64_t frame) {
  const std::filesystem::path file = directory_ / fmt::format("frame_{:05d}.png", frame);
  write_png(image, file);
  ++written_;
  return file;
}

}  // namespace drumlab::render
