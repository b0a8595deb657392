#include "engine/io/atomic_file.hpp"

#include <unistd.h>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab {

std::filesystem::path staging_path(const std::filesystem::path& file, long pid) {
  return file.string() + fmt::format(".tmp-{}", pid);
}

std::filesystem::path staging_path(const std::filesystem::path& file) {
  return staging_path(file, static_cast<long>(::getpid()));
}

InputError cannot_create(const std::filesystem::path& file) {
  return InputError(fmt::format("{}: cannot write (does the directory exist and is it writable?)",
                                file.string()));
}

void write_file_atomically(const std::filesystem::path& file,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path tmp = staging_path(file);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw cannot_create(file);
    write(out);
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw InputError(fmt::format("{}: write failed (disk full?)", file.string()));
    }
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError(fmt::format("{}: cannot rename into place: {}", file.string(), ec.message()));
  }
}

}  // namespace drumlab
