// libFuzzer harness: the bytes as an HDF5 time series (drumlab run --h5), read as `drumlab
// analyze` and the Python module read it: read_series_info, then each of the first frames. Bad
// input must be an InputError; a frame read must have arrays of one length. Anything else
// (another exception, a crash, a sanitizer report) is a finding.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/io/h5_series.hpp"
#include "tests/fuzz/scratch_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const drumlab::fuzz::ScratchFile scratch("drumlab-fuzz-series");
  const fs::path& file = scratch.path();
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const drumlab::SeriesInfo info = drumlab::read_series_info(file);
    for (std::size_t k = 0; k < std::min<std::size_t>(info.frames, 4); ++k) {
      const drumlab::SeriesFrame f = drumlab::read_series_frame(file, k);
      const std::size_t n = f.id.size();
      if (f.position.size() != n || f.velocity.size() != n || f.omega.size() != n ||
          f.radius.size() != n || f.size_class.size() != n) {
        std::abort();  // a frame accepted with arrays of different lengths
      }
    }
  } catch (const drumlab::InputError&) {
  }
  return 0;
}
