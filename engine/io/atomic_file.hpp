#pragma once
// Writes a file under a temporary name and renames it into place only when complete, so a failed
// write never leaves a truncated file under the final name.
#include <filesystem>
#include <functional>
#include <ostream>

#include "engine/types.hpp"

namespace drumlab {

/// FILE.tmp-PID, where a file is built before it is renamed into place; `pid` the writing
/// process's (an MPI run's: rank 0's, so that every rank names the same file).
std::filesystem::path staging_path(const std::filesystem::path& file, long pid);
/// staging_path with this process's pid.
std::filesystem::path staging_path(const std::filesystem::path& file);
/// The one-line error for a file that cannot be created.
InputError cannot_create(const std::filesystem::path& file);

/// Calls `write` with a stream to staging_path(file), then renames it to `file`. Throws InputError
/// naming the file if it cannot be created, written or renamed (the temporary is removed).
void write_file_atomically(const std::filesystem::path& file,
                           const std::function<void(std::ostream&)>& write);

}  // namespace drumlab
