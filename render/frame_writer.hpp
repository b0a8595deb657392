#pragma once
// PNG output. Each file is encoded in memory and written under a temporary name, then renamed, so
// a failed write (bad path, disk full) never leaves a truncated PNG under the final name.
#include <cstdint>
#include <filesystem>
#include <string>

#include "render/image.hpp"

namespace drumlab::render {

/// Writes `image` to `file` as PNG. Throws InputError naming the file on failure.
void write_png(const Image& image, const std::filesystem::path& file);

/// Numbered frames DIR/frame_00000.png, DIR/frame_00001.png, ... (the directory is created).
class FrameWriter {
 public:
  /// Throws InputError if the directory cannot be created.
  explicit FrameWriter(std::filesystem::path directory);
  /// Writes frame `frame` and returns its path.
  std::filesystem::path write(const Image& image, std::uint64_t frame);
  const std::filesystem::path& directory() const { return directory_; }
  /// ffmpeg-style pattern of the frame names, "frame_%05d.png".
  static std::string pattern() { return "frame_%05d.png"; }
  std::uint64_t frames_written() const { return written_; }

 private:
  std::filesystem::path directory_;
  std::uint64_t written_ = 0;
};

}  // namespace drumlab::render
