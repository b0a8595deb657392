#pragma once
// Turns numbered PNG frames into a movie: H.264 MP4 through an `ffmpeg` subprocess, or, when no
// ffmpeg is on the PATH, Ogg/Theora through VTK's writer. The movie is written under a temporary
// name and renamed when complete.
#include <filesystem>
#include <string>

namespace drumlab::render {

struct MovieOptions {
  std::filesystem::path frames_dir;  ///< holds frame_00000.png, frame_00001.png, ...
  std::uint64_t frames = 0;          ///< number of frames
  int fps = 25;
  std::string ffmpeg = "ffmpeg";  ///< program looked up on the PATH
};

/// Full path of `program` on the PATH, or empty if there is none.
std::filesystem::path find_program(const std::string& program);

/// Encodes the frames into `movie` and returns the file actually written: `movie` itself with
/// ffmpeg, or `movie` with the extension .ogv without it. Throws InputError for an unusable path
/// and std::runtime_error if the encoder fails; no partial file is left under the final name.
std::filesystem::path write_movie(const MovieOptions& options, const std::filesystem::path& movie);

}  // namespace drumlab::render
