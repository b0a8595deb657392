#pragma once
// Writes a file under a temporary name and renames it into place only when complete, so a failed
// write never leaves a truncated file under the final name.
#include <filesystem>
#include <functional>
#include <ostream>

namespace drumlab {

/// Calls `write` with a stream to FILE.tmp-XXXX, then renames it to `file`. Throws InputError
/// naming the file if it cannot be created, written or renamed (the temporary is removed).
void write_file_atomically(const std::filesystem::path& file,
                           const std::function<void(std::ostream&)>& write);

}  // namespace drumlab
